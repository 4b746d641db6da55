// Run (src/app/run.hpp) stepped by a driver in chunks writes the outputs and the report of one uninterrupted
// `lpsim run`, finish() may be called again, done() ends a run where `lpsim run` ends it, and
// simulation_options maps a config onto the engine's options.
#include "app/run.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "app/simulation_options.hpp"
#include "converters/cli_options.hpp"
#include "lpsim_cli.hpp"
#include "temp_dir.hpp"

namespace lpsim {
namespace {

namespace fs = std::filesystem;

constexpr double kForever = std::numeric_limits<double>::infinity();

// Periodic edgeData and laneData (several intervals each, the last one cut short by the end of the run);
// the file names are relative to the add-file's folder.
const char* const kMeanDataAdditional = R"(<additional>
    <edgeData id="per_minute" file="edgedata_periodic.xml" period="60"/>
    <laneData id="lanes" file="lanedata_periodic.xml" freq="45"/>
</additional>
)";

const std::vector<std::string> kOutputFiles{
    "fcd.xml",      "tripinfo.xml",         "summary.xml", "edgedata.xml", "edgedata_periodic.xml",
    "lanedata.xml", "lanedata_periodic.xml"};

std::vector<std::string> sumo_input(const std::string& scenario) {
  return {"-c", std::string(LPSIM_SCENARIOS_DIR) + "/" + scenario + "/" + scenario + ".sumocfg"};
}

std::vector<std::string> csv_input() {
  const std::string dir = std::string(LPSIM_SCENARIOS_DIR) + "/lpsim_csv_small/";
  return {"--lpsim-nodes",   dir + "nodes.csv", "--lpsim-edges",
          dir + "edges.csv", "--lpsim-od",      dir + "od.csv"};
}

// `input` and `options`, then every output in `dir` (relative names when `dir` is empty: the command runs
// there), with the periodic edgeData/laneData add-file written to `dir_for_additional`.
std::vector<std::string> run_args(const std::vector<std::string>& input,
                                  const std::vector<std::string>& options, const fs::path& dir_for_additional,
                                  const fs::path& dir) {
  const std::string additional = (dir_for_additional / "meandata.add.xml").string();
  std::ofstream(additional, std::ios::binary) << kMeanDataAdditional;
  std::vector<std::string> args = input;
  args.insert(args.end(), options.begin(), options.end());
  args.insert(args.end(), {"-a", additional, "--no-warnings"});
  for (const auto& [option, file] : {std::pair{"--fcd-output", "fcd.xml"},
                                     {"--tripinfo-output", "tripinfo.xml"},
                                     {"--summary-output", "summary.xml"},
                                     {"--edgedata-output", "edgedata.xml"},
                                     {"--lanedata-output", "lanedata.xml"}})
    args.insert(args.end(), {option, (dir / file).string()});
  return args;
}

// The summary's duration attribute and the report's performance lines (but the vehicle updates and threads)
// are wall time.
std::string mask_wall_time(const std::string& text) {
  static const std::regex duration(" duration=\"[^\"]*\"");
  std::istringstream lines(std::regex_replace(text, duration, " duration=\"masked\""));
  std::string masked;
  for (std::string line; std::getline(lines, line);) {
    const bool wall = (line.starts_with(" Duration: ") && line.find("(load ") != std::string::npos) ||
                      line.starts_with(" Real time factor: ") || line.starts_with(" UPS: ") ||
                      line.starts_with(" Steps: ");
    masked += wall ? std::string(" (wall time)") : line;
    masked += '\n';
  }
  return masked;
}

size_t count_of(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

std::string report_of(const Run& run) {
  std::FILE* f = std::tmpfile();
  if (f == nullptr) return "(no temporary file for the report)";
  print_run_report(f, run, 1.0, 0.5);
  std::string text(static_cast<size_t>(std::ftell(f)), '\0');
  std::rewind(f);
  text.resize(std::fread(text.data(), 1, text.size(), f));
  std::fclose(f);
  return text;
}

struct ChunkCase {
  friend void PrintTo(const ChunkCase& c, std::ostream* os) { *os << c.name; }
  const char* name;
  std::vector<std::string> input;    // the scenario
  std::vector<std::string> options;  // further `lpsim run` options
  std::vector<double> chunks;        // step_until() targets, in order
  bool teleports;                    // the case must teleport vehicles
};

class RunChunksTest : public ::testing::TestWithParam<ChunkCase> {};

TEST_P(RunChunksTest, WritesWhatLpsimRunWrites) {
  const ChunkCase& c = GetParam();
  const test::TempDir tmp("lpsim_run_chunks");
  const fs::path cli_dir = tmp.path() / "cli", run_dir = tmp.path() / "run";
  fs::create_directories(cli_dir);
  fs::create_directories(run_dir);

  std::vector<std::string> cli_args{"run"};
  for (const std::string& a : run_args(c.input, c.options, cli_dir, "")) cli_args.push_back(a);
  const test::CliResult cli = test::run_lpsim(cli_dir, cli_args);
  ASSERT_EQ(cli.exit_code, 0) << cli.out << cli.err;

  const ConfigSpec config = parse_cli_options(run_args(c.input, c.options, run_dir, run_dir));
  const Scenario sc = load_scenario(config);
  lpsim::Run run(sc, config, simulation_options(config));  // qualified: a TEST body sees testing::Test::Run
  const double step = config.step_length;
  for (const double t : c.chunks) {
    run.step_until(t);
    const double now = run.simulation().time();
    EXPECT_LE(now, t + 1e-9) << "step_until(" << t << ") stepped past it";
    if (!run.done()) {
      EXPECT_GT(now + step, t + 1e-9) << "step_until(" << t << ") stopped early at " << now;
    }
  }
  ASSERT_TRUE(run.done()) << "the chunks end the run";
  run.finish();

  if (c.teleports) {
    EXPECT_GT(run.simulation().counts().teleports, 0u);
  }
  EXPECT_GT(run.totals().trips, 0u);
  for (const std::string& name : kOutputFiles) {
    const std::string expected = test::read_file(cli_dir / name);
    EXPECT_GT(expected.size(), 100u) << name;
    EXPECT_TRUE(mask_wall_time(test::read_file(run_dir / name)) == mask_wall_time(expected))
        << name << " differs from `lpsim run`'s";
  }
  EXPECT_GE(count_of(test::read_file(run_dir / "edgedata_periodic.xml"), "<interval "), 3u);
  EXPECT_EQ(mask_wall_time(report_of(run)), mask_wall_time(cli.out));
}

INSTANTIATE_TEST_SUITE_P(
    BundledScenarios, RunChunksTest,
    ::testing::Values(ChunkCase{"GridTlsWithTeleports",
                                sumo_input("grid_tls"),
                                {"--end", "600", "--time-to-teleport", "20"},
                                {100, 100, 237.3, 401, kForever},
                                true},
                      ChunkCase{"FlowsHalfSecondSteps",
                                sumo_input("flows"),
                                {"--end", "500", "--step-length", "0.5", "--device.fcd.period", "2"},
                                {0.2, 100, 333.3, 500},
                                false},
                      ChunkCase{"CsvUntilAllArrived", csv_input(), {}, {50, 50.5, 173, kForever}, false}),
    [](const ::testing::TestParamInfo<ChunkCase>& info) { return std::string(info.param.name); });

// A Run of grid_tls with `options` and every output in `dir`.
struct GridRun {
  GridRun(const fs::path& dir, const std::vector<std::string>& options)
      : config(parse_cli_options(run_args(sumo_input("grid_tls"), options, dir, dir))),
        scenario(load_scenario(config)),
        run(scenario, config, simulation_options(config)) {}
  ConfigSpec config;
  Scenario scenario;
  lpsim::Run run;
};

TEST(RunTest, FinishTwiceChangesNothing) {
  const test::TempDir tmp("lpsim_run_finish");
  GridRun g(tmp.path(), {"--end", "150"});
  g.run.step_until(kForever);
  g.run.finish();
  const auto closing_tag = [](const std::string& name) {
    return name == "fcd.xml"        ? "</fcd-export>\n"
           : name == "tripinfo.xml" ? "</tripinfos>\n"
           : name == "summary.xml"  ? "</summary>\n"
                                    : "</meandata>\n";
  };
  std::vector<std::string> after_first;
  for (const std::string& name : kOutputFiles) {
    after_first.push_back(test::read_file(tmp.path() / name));
    EXPECT_TRUE(after_first.back().ends_with(closing_tag(name))) << name << " is not closed after finish()";
  }
  // finish() wrote the open intervals up to the end of the run (150, as SUMO: the end of the last step).
  const std::string periodic = test::read_file(tmp.path() / "edgedata_periodic.xml");
  const std::string whole = test::read_file(tmp.path() / "edgedata.xml");
  EXPECT_EQ(count_of(periodic, "<interval "), 3u) << periodic.substr(0, 2000);
  EXPECT_NE(periodic.find("<interval begin=\"120.00\" end=\"150.00\""), std::string::npos);
  EXPECT_NE(whole.find("<interval begin=\"0.00\" end=\"150.00\""), std::string::npos);
  EXPECT_NO_THROW(g.run.finish());
  for (size_t k = 0; k < kOutputFiles.size(); ++k)
    EXPECT_TRUE(test::read_file(tmp.path() / kOutputFiles[k]) == after_first[k])
        << kOutputFiles[k] << " changed at the second finish()";
  EXPECT_THROW(g.run.step(), std::logic_error);
}

// The Run's own actions run after each step in their order, and an action a driver adds runs after them, from
// the next step on, at its trigger's times.
TEST(RunTest, ActionsRunAfterEachStepInOrder) {
  const test::TempDir tmp("lpsim_run_actions");
  GridRun g(tmp.path(), {"--end", "150", "--no-warnings"});
  EXPECT_EQ(g.run.actions().names(),
            (std::vector<std::string>{"totals", "fcd", "tripinfo", "summary", "interval per_minute",
                                      "interval lanes", "flush"}));
  std::vector<double> when, state;
  g.run.add_action("probe", StepTrigger::every(30, 30), [&](double t) {
    when.push_back(t);
    state.push_back(g.run.simulation().time());
  });
  g.run.step_until(kForever);
  g.run.finish();
  EXPECT_EQ(when, (std::vector<double>{30, 60, 90, 120}));
  EXPECT_EQ(state, when);  // on the state of the step that reached the time (1 s steps)
}

// As `lpsim run`: with an end time the run is done once one more step would end after it (as SUMO, at
// end - step when the end is a whole number of steps after the begin), and step_until() goes no further.
TEST(RunTest, DoneFollowsTheEndTime) {
  const test::TempDir tmp("lpsim_run_done");
  // begin, step length, end, the time the run ends at
  for (const auto& [begin, step, end, last] :
       {std::tuple{0.0, 1.0, 10.0, 9.0}, {5.0, 0.5, 12.0, 11.5}, {0.0, 2.0, 9.0, 8.0}}) {
    const std::string what =
        "begin " + std::to_string(begin) + " step " + std::to_string(step) + " end " + std::to_string(end);
    GridRun g(tmp.path(), {"--begin", std::to_string(begin), "--step-length", std::to_string(step), "--end",
                           std::to_string(end)});
    const Simulation& sim = g.run.simulation();
    EXPECT_EQ(sim.time(), begin) << what;
    while (!g.run.done()) {
      EXPECT_LT(sim.time() + step, end + 1e-9) << what << ": a step ending after the end time is due";
      g.run.step();
    }
    EXPECT_EQ(sim.time(), last) << what;
    g.run.step_until(end + 100);
    EXPECT_EQ(sim.time(), last) << what << ": step_until() stepped a done run";
    g.run.finish();
  }
}

TEST(RunTest, WithoutEndTimeDoneWhenAllVehiclesLeft) {
  const test::TempDir tmp("lpsim_run_no_end");
  const ConfigSpec config = parse_cli_options(run_args(csv_input(), {}, tmp.path(), tmp.path()));
  ASSERT_LT(config.end, 0);
  const Scenario sc = load_scenario(config);
  lpsim::Run run(sc, config, simulation_options(config));
  uint64_t steps = 0;
  while (!run.done()) {
    EXPECT_FALSE(run.simulation().finished());
    run.step();
    ++steps;
  }
  EXPECT_TRUE(run.simulation().finished());
  EXPECT_GT(steps, 10u);
  EXPECT_EQ(run.simulation().counts().arrived, run.simulation().counts().loaded);
  run.finish();
}

// The engine counts per-lane traffic (and pays its atomics) exactly when an edgeData/laneData output needs
// it.
TEST(RunTest, LaneCountersFollowTheMeanDataOutputs) {
  const test::TempDir tmp("lpsim_run_counters");
  const Scenario sc = load_scenario(parse_cli_options(sumo_input("grid_tls")));
  ConfigSpec config = sc.config;
  config.end = 60;
  SimulationOptions asked = simulation_options(config);
  asked.lane_counters = true;
  EXPECT_FALSE(lpsim::Run(sc, config, asked).options().lane_counters) << "no output needs them";
  config.outputs.edgedata = (tmp.path() / "edgedata.xml").string();
  asked.lane_counters = false;
  lpsim::Run run(sc, config, asked);
  EXPECT_TRUE(run.options().lane_counters) << "edgeData needs them";
  run.step_until(kForever);
  int64_t sampled = 0;
  for (const int64_t s : run.simulation().collect_lane_counters().sampled_steps) sampled += s;
  EXPECT_GT(sampled, 0);
  run.finish();
}

TEST(SimulationOptionsTest, MapsEveryEngineFieldOfTheConfig) {
  ConfigSpec config;
  config.begin = 12.5;
  config.step_length = 0.25;
  config.seed = 987654321012LL;
  config.threads = 3;
  config.time_to_teleport = 42;
  config.device = ComputeDevice::Gpu;
  const SimulationOptions o = simulation_options(config);
  EXPECT_EQ(o.begin, 12.5);
  EXPECT_EQ(o.step_ms, 250);
  EXPECT_EQ(o.seed, 987654321012u);
  EXPECT_EQ(o.threads, 3);
  EXPECT_EQ(o.time_to_teleport, 42);
  // Left to the driver (device probing) and to Run (outputs): the engine's defaults.
  const SimulationOptions defaults;
  EXPECT_EQ(o.backend, &make_cpu_stepper);
  EXPECT_EQ(o.lane_counters, defaults.lane_counters);
  EXPECT_EQ(o.slot_sort_interval, defaults.slot_sort_interval);
}

TEST(SimulationOptionsTest, NoThreadCountStepsOnOneThread) {
  ConfigSpec config;
  ASSERT_EQ(config.threads, 0);
  EXPECT_EQ(simulation_options(config).threads, 1);
}

TEST(SimulationOptionsTest, CommandLineReachesTheEngine) {
  const SimulationOptions o =
      simulation_options(parse_cli_options({"--begin", "0:01:00", "--step-length", "0.5", "--seed", "7",
                                            "--threads", "2", "--time-to-teleport", "-1"}));
  EXPECT_EQ(o.begin, 60);
  EXPECT_EQ(o.step_ms, 500);
  EXPECT_EQ(o.seed, 7u);
  EXPECT_EQ(o.threads, 2);
  EXPECT_EQ(o.time_to_teleport, -1);
}

}  // namespace
}  // namespace lpsim

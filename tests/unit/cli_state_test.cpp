// `lpsim run --save-state.times T` and `--load-state`: a run resumed from the state saved at T writes every
// output byte for byte as the uninterrupted run does (its outputs continued from where the saved run had
// written them), in one part and in 3 whatever parts saved it, saving changes no output, and a state file
// that is not one of this run is refused with one line and exit status 2. Every bundled scenario, each in a
// copy (their add-file outputs land beside them).
#include <gtest/gtest.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include "converters/input_file.hpp"
#include "lpsim_cli.hpp"
#include "meandata_entries.hpp"
#include "temp_dir.hpp"
#include "unit/spawned_lpsim.hpp"

namespace lpsim {
namespace {

namespace fs = std::filesystem;
using test::CliResult;
using test::read_file;

// Every file a run wrote into `dir` (its outputs, the scenario's add-file outputs), by name; not the
// scenario's own files, the run's logs or state files.
std::vector<std::pair<std::string, std::string>> outputs_in(const fs::path& dir,
                                                            const std::string& scenario) {
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& f : fs::directory_iterator(dir)) {
    const std::string name = f.path().filename().string();
    if (fs::exists(fs::path(LPSIM_SCENARIOS_DIR) / scenario / name) || name == "stdout.txt" ||
        name == "stderr.txt" || name.find(".lpstate") != std::string::npos)
      continue;
    out.emplace_back(name, read_file(f.path()));
  }
  std::sort(out.begin(), out.end());
  return out;
}

// The outputs both tests compare: FCD, tripinfo, summary, edgeData and statistic.
std::vector<std::string> compared_outputs() {
  return {"--fcd-output", "fcd.xml",           "--tripinfo-output", "tripinfo.xml",       "--summary-output",
          "summary.xml",  "--edgedata-output", "edgedata.xml",      "--statistic-output", "statistic.xml"};
}

class CliStateTest : public ::testing::TestWithParam<std::string> {
 protected:
  // The scenario copied to `sub`, run there with every output and `extra`.
  CliResult run_in(const std::string& sub, const std::vector<std::string>& extra) {
    const fs::path dir = tmp_.path() / sub;
    if (!fs::exists(dir)) test::copy_scenario(GetParam(), dir);
    std::vector<std::string> args{"run", "-c", GetParam() + ".sumocfg", "--no-step-log", "-W"};
    const std::vector<std::string> outputs = compared_outputs();
    args.insert(args.end(), outputs.begin(), outputs.end());
    for (const char* a : {"--lanedata-output", "lanedata.xml", "--tripinfo-output.write-unfinished"})
      args.emplace_back(a);
    args.insert(args.end(), extra.begin(), extra.end());
    return test::run_lpsim(dir, args);
  }
  // A time well inside the run: 40 % of the way from its begin to its end (a whole second).
  std::string save_time() const {
    const std::string cfg = read_file(fs::path(LPSIM_SCENARIOS_DIR) / GetParam() / (GetParam() + ".sumocfg"));
    std::smatch m;
    const double end =
        std::regex_search(cfg, m, std::regex("<end value=\"([0-9.]+)\"")) ? std::stod(m[1]) : 1000;
    return std::to_string(static_cast<int>(end * 0.4));
  }
  test::TempDir tmp_{"lpsim_state"};
};

TEST_P(CliStateTest, AResumedRunWritesEveryOutputAsTheUninterruptedOne) {
  const CliResult whole = run_in("whole", {});
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  const auto expected = outputs_in(tmp_.path() / "whole", GetParam());
  ASSERT_GE(expected.size(), 6u);

  const std::string t = save_time();
  const CliResult saving = run_in("saved", {"--save-state.times", t});
  ASSERT_EQ(saving.exit_code, 0) << saving.err;
  const std::string state = "state_" + t + ".00.lpstate";
  ASSERT_TRUE(fs::exists(tmp_.path() / "saved" / state)) << state;
  EXPECT_EQ(outputs_in(tmp_.path() / "saved", GetParam()), expected) << "saving changed an output";

  // Resumed (on 2 threads: the results do not depend on them) over the outputs the saving run left, which
  // ran on past the save as those of a run pre-empted after it would have.
  const CliResult resumed = run_in("saved", {"--load-state", state, "--threads", "2"});
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_NE(resumed.err.find("resumed from " + state + " at time " + t + ".00"), std::string::npos)
      << resumed.err;
  EXPECT_EQ(outputs_in(tmp_.path() / "saved", GetParam()), expected) << "resumed at " << t;

  // And in 3 parts, the state re-cut for them.
  const CliResult in_parts =
      run_in("saved", {"--load-state", state, "--parts", "3", "--parts.min-vehicles", "0"});
  ASSERT_EQ(in_parts.exit_code, 0) << in_parts.err;
  EXPECT_EQ(outputs_in(tmp_.path() / "saved", GetParam()), expected) << "resumed at " << t << " in 3 parts";
}

// A partitioned run saves every part's state in one file, and the same parts, or others, resumed from it go
// on as the run never stopped (whose outputs are those of one part).
TEST_P(CliStateTest, APartitionedRunResumedInAnyPartsWritesEveryOutputAsTheUninterruptedOne) {
  const CliResult whole = run_in("whole", {});
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  const auto expected = outputs_in(tmp_.path() / "whole", GetParam());
  const std::string t = save_time();
  const std::vector<std::string> parts{"--parts", "3", "--parts.min-vehicles", "0"};
  std::vector<std::string> saving = parts;
  saving.insert(saving.end(), {"--save-state.times", t});
  const CliResult saved = run_in("parts", saving);
  ASSERT_EQ(saved.exit_code, 0) << saved.err;
  EXPECT_EQ(outputs_in(tmp_.path() / "parts", GetParam()), expected) << "saving changed an output";
  std::vector<std::string> resuming = parts;
  resuming.insert(resuming.end(), {"--load-state", "state_" + t + ".00.lpstate", "--threads", "2"});
  const CliResult resumed = run_in("parts", resuming);
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_EQ(outputs_in(tmp_.path() / "parts", GetParam()), expected) << "resumed at " << t;

  // And in other parts, the state re-cut for them: one part, and two.
  const std::string state = "state_" + t + ".00.lpstate";
  const CliResult in_one = run_in("parts", {"--load-state", state, "--threads", "2"});
  ASSERT_EQ(in_one.exit_code, 0) << in_one.err;
  EXPECT_EQ(outputs_in(tmp_.path() / "parts", GetParam()), expected) << "resumed at " << t << " in one part";
  const CliResult in_two =
      run_in("parts", {"--load-state", state, "--parts", "2", "--parts.min-vehicles", "0"});
  ASSERT_EQ(in_two.exit_code, 0) << in_two.err;
  EXPECT_EQ(outputs_in(tmp_.path() / "parts", GetParam()), expected) << "resumed at " << t << " in 2 parts";
}

INSTANTIATE_TEST_SUITE_P(BundledScenarios, CliStateTest,
                         ::testing::Values("grid_tls", "actuated_cross", "city_mixed", "flows", "keep_clear",
                                           "motorway_ramps", "random_net", "reroute_block",
                                           "emissions_classes", "emissions_free", "emissions_redlight",
                                           "cosim_line"));

// A batch job pre-empted: SIGTERM stops the run at a step's end, --save-state.on-signal saves its state
// before the outputs close, and the job started again with --load-state ends with the outputs of the run that
// was never stopped. grid_tls run on far past its demand (empty steps), so that the signal lands mid-run.
TEST(CliStateSignalTest, APreemptedRunResumedFromTheStateItSavedOnTheSignalWritesTheSameOutputs) {
  test::TempDir tmp("lpsim_state_signal");
  std::vector<std::string> args{"run", "-c", std::string(LPSIM_SCENARIOS_DIR) + "/grid_tls/grid_tls.sumocfg",
                                "--end", "40000"};
  const std::vector<std::string> outputs = compared_outputs();
  args.insert(args.end(), outputs.begin(), outputs.end());
  for (const char* a : {"--no-warnings", "--progress-interval", "0.02"}) args.emplace_back(a);
  fs::create_directories(tmp.path() / "whole");
  fs::create_directories(tmp.path() / "stopped");
  const CliResult whole = test::run_lpsim(tmp.path() / "whole", args);
  ASSERT_EQ(whole.exit_code, 0) << whole.err;

  std::vector<std::string> stopping = args;
  stopping.push_back("--save-state.on-signal");
  test::SpawnedLpsim lpsim(tmp.path() / "stopped", stopping);
  ASSERT_TRUE(lpsim.started());
  // The simulation time of the last progress line ("lpsim: t=12.00 running ..."), or -1.
  auto progress = [&lpsim] {
    static const std::regex line(R"(lpsim: t=([0-9.]+) running )");
    const std::string err = lpsim.err();
    double t = -1;
    for (auto it = std::sregex_iterator(err.begin(), err.end(), line); it != std::sregex_iterator(); ++it)
      t = std::stod((*it)[1].str());
    return t;
  };
  ASSERT_TRUE(lpsim.wait_until([&] { return progress() >= 150; }, 8)) << lpsim.err();
  lpsim.send(SIGTERM);
  const int status = lpsim.wait_exit(8);
  ASSERT_TRUE(WIFEXITED(status)) << lpsim.err();
  ASSERT_EQ(WEXITSTATUS(status), 128 + SIGTERM) << lpsim.err();
  std::smatch saved;
  const std::string err = lpsim.err();
  ASSERT_TRUE(std::regex_search(err, saved, std::regex(R"(lpsim: state saved to (state_[0-9.]+\.lpstate))")))
      << err;

  std::vector<std::string> resume = args;
  resume.insert(resume.end(), {"--load-state", saved[1].str()});
  const CliResult resumed = test::run_lpsim(tmp.path() / "stopped", resume);
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  for (const std::string name : {"fcd.xml", "tripinfo.xml", "summary.xml", "edgedata.xml", "statistic.xml"})
    EXPECT_TRUE(read_file(tmp.path() / "whole" / name) == read_file(tmp.path() / "stopped" / name))
        << name << " after resuming from " << saved[1].str();
}

// The text of a file, gunzipped when it is gzip (InputFile reads concatenated members as one text).
std::string text_of(const fs::path& path) {
  InputFile in(path.string());
  std::string text;
  char chunk[1 << 16];
  for (size_t n; (n = in.read(chunk, sizeof chunk)) > 0;) text.append(chunk, n);
  return text;
}

// Gzipped outputs are continued too: the save ends each one's gzip member, and the resumed run appends a
// member of its own, so that the text decompressed is the uninterrupted run's (and saving changes no text).
TEST(CliStateGzipTest, AResumedRunContinuesGzippedOutputsAsOneText) {
  test::TempDir tmp("lpsim_state_gzip");
  const std::vector<std::string> gzipped{"fcd.xml.gz", "tripinfo.xml.gz", "edgedata.xml.gz",
                                         "lanedata.xml.gz"};
  std::vector<std::string> args{"run",
                                "-c",
                                "city_mixed.sumocfg",
                                "--fcd-output",
                                gzipped[0],
                                "--tripinfo-output",
                                gzipped[1],
                                "--edgedata-output",
                                gzipped[2],
                                "--lanedata-output",
                                gzipped[3],
                                "--summary-output",
                                "summary.xml",
                                "--tripinfo-output.write-unfinished",
                                "--no-step-log",
                                "-W"};
  for (const char* dir : {"whole", "saved"}) test::copy_scenario("city_mixed", tmp.path() / dir);
  const CliResult whole = test::run_lpsim(tmp.path() / "whole", args);
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  std::vector<std::string> saving = args;
  saving.insert(saving.end(), {"--save-state.times", "500"});
  const CliResult saved = test::run_lpsim(tmp.path() / "saved", saving);
  ASSERT_EQ(saved.exit_code, 0) << saved.err;
  for (const std::string& f : gzipped)
    EXPECT_TRUE(text_of(tmp.path() / "whole" / f) == text_of(tmp.path() / "saved" / f))
        << f << " after saving";
  std::vector<std::string> resuming = args;
  resuming.insert(resuming.end(), {"--load-state", "state_500.00.lpstate"});
  const CliResult resumed = test::run_lpsim(tmp.path() / "saved", resuming);
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  for (const std::string& f : gzipped) {
    const std::string text = text_of(tmp.path() / "saved" / f);
    EXPECT_GT(text.size(), 1000u) << f;
    EXPECT_TRUE(text_of(tmp.path() / "whole" / f) == text) << f << " after resuming";
  }
  EXPECT_TRUE(read_file(tmp.path() / "whole" / "summary.xml") ==
              read_file(tmp.path() / "saved" / "summary.xml"));
}

// The jam report goes on too: the episodes standing at the save are ended (and written) by the resumed run
// as by the run never stopped, each with the snapshot of the step it was last seen in.
TEST(CliStateJamReportTest, AResumedRunWritesTheJamReportOfTheUninterruptedOne) {
  test::TempDir tmp("lpsim_state_jam");
  for (const std::string name : {"grid_tls", "keep_clear"}) {
    const std::vector<std::string> args{"run",
                                        "-c",
                                        name + ".sumocfg",
                                        "--jam-report",
                                        "jam.xml",
                                        "--jam-report.stop-time",
                                        "20",
                                        "--tripinfo-output",
                                        "trip.xml",
                                        "--no-step-log",
                                        "-W"};
    for (const char* dir : {"whole", "saved"}) test::copy_scenario(name, tmp.path() / name / dir);
    const CliResult whole = test::run_lpsim(tmp.path() / name / "whole", args);
    ASSERT_EQ(whole.exit_code, 0) << whole.err;
    std::vector<std::string> saving = args, resuming = args;
    saving.insert(saving.end(), {"--save-state.times", "700"});
    resuming.insert(resuming.end(), {"--load-state", "state_700.00.lpstate"});
    ASSERT_EQ(test::run_lpsim(tmp.path() / name / "saved", saving).exit_code, 0);
    const CliResult resumed = test::run_lpsim(tmp.path() / name / "saved", resuming);
    ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
    const std::string report = read_file(tmp.path() / name / "whole" / "jam.xml");
    EXPECT_GT(std::count(report.begin(), report.end(), '\n'), 100) << name;
    for (const char* f : {"jam.xml", "trip.xml"})
      EXPECT_TRUE(read_file(tmp.path() / name / "whole" / f) == read_file(tmp.path() / name / "saved" / f))
          << name << ": " << f;
  }
}

class CliStateRefusalTest : public ::testing::Test {
 protected:
  CliResult run(const std::vector<std::string>& args) { return test::run_lpsim(tmp_.path(), args); }
  const std::string grid_ = std::string(LPSIM_SCENARIOS_DIR) + "/grid_tls/grid_tls.sumocfg";
  const std::string flows_ = std::string(LPSIM_SCENARIOS_DIR) + "/flows/flows.sumocfg";
  test::TempDir tmp_{"lpsim_state_refusal"};
};

TEST_F(CliStateRefusalTest, AStateThatIsNotOneOfThisRunIsRefusedWithOneLine) {
  ASSERT_EQ(
      run({"run", "-c", grid_, "--no-step-log", "-W", "--save-state.times", "200", "--end", "300"}).exit_code,
      0);
  const std::string good = read_file(tmp_.path() / "state_200.00.lpstate");
  ASSERT_GT(good.size(), 100u);
  auto write = [&](const std::string& name, const std::string& bytes) {
    std::ofstream(tmp_.path() / name, std::ios::binary) << bytes;
  };
  write("cut.lpstate", good.substr(0, good.size() - 10));
  std::string flipped = good;
  flipped[flipped.size() / 2] = static_cast<char>(flipped[flipped.size() / 2] ^ 0x40);
  write("flipped.lpstate", flipped);
  std::string version = good;
  version[8] = static_cast<char>(version[8] + 1);  // the format version follows the 8-byte magic
  write("version.lpstate", version);
  write("text.lpstate", "<snapshot/>\n");
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases{
      {{"run", "-c", grid_, "--load-state", "cut.lpstate"}, "truncated"},
      {{"run", "-c", grid_, "--load-state", "flipped.lpstate"}, "corrupted"},
      {{"run", "-c", grid_, "--load-state", "version.lpstate"}, "format version"},
      {{"run", "-c", grid_, "--load-state", "text.lpstate"}, "not an LPSim state file"},
      {{"run", "-c", grid_, "--load-state", "missing.lpstate"}, "cannot read"},
      {{"run", "-c", flows_, "--load-state", "state_200.00.lpstate"}, "another scenario"},
      {{"run", "-c", grid_, "--seed", "7", "--load-state", "state_200.00.lpstate"}, "other options"},
  };
  for (const auto& [args, why] : cases) {
    std::vector<std::string> a = args;
    a.insert(a.end(), {"--no-step-log", "-W"});
    const CliResult r = run(a);
    EXPECT_EQ(r.exit_code, 2) << args.back() << ": " << r.err;
    EXPECT_EQ(test::lines_of(r.err).size(), 1u) << r.err;
    EXPECT_NE(r.err.find(why), std::string::npos) << r.err;
  }
}

}  // namespace
}  // namespace lpsim

// The co-simulation with the real SUMO (label cosim): LPSim runs a bundled scenario while SUMO drives a
// corridor of it, in process (libsumo) and as a sumo process over TraCI. Every step, every loaded vehicle is
// in exactly one place (LPSim's ledger, the bridge's account and SUMO's own counts agree); every trip that
// ended has one tripinfo line for its whole trip; the outputs of both sides validate against SUMO's XSDs.
// The spillback tests put a queue downstream of the corridor (LPSim full: vehicles held in SUMO) and inside
// it (SUMO full: LPSim's vehicles wait at the boundary); routes may cross the corridor twice; SUMO killed
// mid-run is one error with LPSim's outputs closed well-formed.
#include "sumo_bridge/cosimulation.hpp"

#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "app/corridor_resolution.hpp"
#include "app/scenario_args.hpp"
#include "app/simulation_options.hpp"
#include "converters/sumo_tripinfo_reader.hpp"
#include "converters/xml_stream.hpp"
#include "lpsim_cli.hpp"
#include "sumo_bridge/sumo_arguments.hpp"
#include "sumo_schema.hpp"
#include "temp_dir.hpp"
#include "unit/spawned_lpsim.hpp"

namespace lpsim {
namespace {

namespace fs = std::filesystem;

const std::string kScenarios = LPSIM_SCENARIOS_DIR;
const std::string kGrid = kScenarios + "/grid_tls/grid_tls.sumocfg";
const std::string kLine = kScenarios + "/cosim_line/cosim_line.sumocfg";
// The middle row of the 5x5 grid, both ways: routes enter it, leave it, start and end on it.
const std::vector<std::string> kGridCorridor{"A2B2", "B2C2", "C2D2", "D2E2", "E2D2", "D2C2", "C2B2", "B2A2"};

struct Outcome {
  Cosimulation::Report report;
  Cosimulation::Census last;
  uint64_t steps = 0, most_in_sumo = 0, most_in_handover = 0;
  uint64_t lpsim_arrived = 0;              // trips written by the run (merged ones included)
  std::map<std::string, int> hand_ins;     // per vehicle id: times handed into SUMO
  int steps_lpsim_queued_at_boundary = 0;  // steps with a standing LPSim vehicle on `watch_lane`'s end
  fs::path tripinfo, summary, fcd, edgedata;
};

struct Case {
  Case(std::string cfg_, std::vector<std::string> corridor_, SumoMode mode_ = SumoMode::Libsumo)
      : cfg(std::move(cfg_)), corridor(std::move(corridor_)), mode(mode_) {}
  std::string cfg;
  std::vector<std::string> corridor;
  SumoMode mode;
  std::vector<std::string> extra_args;  // lpsim options
  std::vector<std::string> sumo_args;
  std::string watch_lane;    // an LPSim lane just before the corridor
  int kill_sumo_after = -1;  // steps; over TraCI
};

Outcome run_case(const Case& c, const test::TempDir& dir) {
  Outcome o;
  o.tripinfo = fs::path(dir.path()) / "tripinfo.xml";
  o.summary = fs::path(dir.path()) / "summary.xml";
  o.fcd = fs::path(dir.path()) / "fcd.xml";
  o.edgedata = fs::path(dir.path()) / "edgedata.xml";
  std::vector<std::string> args{"-c",
                                c.cfg,
                                "--tripinfo-output",
                                o.tripinfo.string(),
                                "--summary-output",
                                o.summary.string(),
                                "--fcd-output",
                                o.fcd.string(),
                                "--edgedata-output",
                                o.edgedata.string(),
                                "--no-step-log",
                                "--no-warnings"};
  args.insert(args.end(), c.extra_args.begin(), c.extra_args.end());
  ConfigSpec config;
  Scenario sc = scenario_from_args(args, &config, CliCommand::Cosim);
  std::vector<uint32_t> edges;
  for (const std::string& id : c.corridor) edges.push_back(sc.network.edge_index.at(id));
  std::sort(edges.begin(), edges.end());
  // As `lpsim cosim` takes a corridor: closed over its junctions.
  const std::vector<uint8_t> lanes = corridor_lanes(sc.network, close_corridor(edges, sc.network));
  int32_t watch = -1;
  if (!c.watch_lane.empty()) watch = static_cast<int32_t>(sc.network.lane_index_by_id.at(c.watch_lane));
  SimulationOptions options = simulation_options(config);
  options.outside_lanes = &lanes;
  Run run(std::move(sc), config, options);
  CosimOptions co_opt;
  co_opt.mode = c.mode;
  co_opt.sumo_args = c.sumo_args;
  co_opt.answer_timeout_s = 30;
  Cosimulation co(run, co_opt);
  const Simulation& sim = run.simulation();
  const float watch_length =
      watch >= 0 ? run.scenario().network.lane_length[static_cast<uint32_t>(watch)] : 0;
  while (!co.done()) {
    if (c.kill_sumo_after >= 0 && o.steps == static_cast<uint64_t>(c.kill_sumo_after))
      ::kill(co.sumo().process_id(), SIGKILL);
    try {
      co.step();
    } catch (const SumoError&) {
      co.abandon();
      throw;
    }
    ++o.steps;
    for (const OutsideLink::HandOut& h : run.simulation().outside_link().hand_outs())
      ++o.hand_ins[sim.demand().vehicle_id[h.vehicle]];
    o.last = co.census();  // throws when a vehicle is lost or in two places
    o.most_in_sumo = std::max(o.most_in_sumo, o.last.in_sumo);
    o.most_in_handover = std::max(o.most_in_handover, o.last.in_handover);
    if (watch >= 0)
      for (const uint32_t v : sim.active())
        if (sim.query().lane(v) == watch && sim.query().speed(v) < 0.1f &&
            sim.query().pos(v) > watch_length - 10.0f) {
          ++o.steps_lpsim_queued_at_boundary;
          break;
        }
    if (o.steps > 20000) ADD_FAILURE() << "no end";
    if (o.steps > 20000) break;
  }
  co.finish();
  o.report = co.report();
  o.lpsim_arrived = run.totals().trips;
  return o;
}

std::string read_all(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

double reference_value(const std::string& cfg, const std::string& key) {
  const std::string text = read_all(fs::path(cfg).parent_path() / "sumo_reference.txt");
  const std::regex re("(^|\n)" + key + "=([0-9.]+)");
  std::smatch m;
  if (!std::regex_search(text, m, re)) throw std::runtime_error(key + " not in the reference");
  return std::stod(m[2]);
}

void expect_valid(const fs::path& file, const std::string& xsd, const test::TempDir& dir) {
  if (std::system("xmllint --version > /dev/null 2>&1") != 0) GTEST_SKIP() << "xmllint not installed";
  const std::string schema = test::usable_sumo_schema(std::string(test::kSumoXsdDir) + "/" + xsd, dir);
  const fs::path log = fs::path(dir.path()) / (file.filename().string() + ".xmllint.log");
  const std::string cmd =
      "xmllint --noout --schema " + schema + " " + file.string() + " > " + log.string() + " 2>&1";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << file << " fails " << xsd << ":\n"
                                         << read_all(log).substr(0, 2000);
}

// Every output of both sides, against SUMO's schemas.
void expect_outputs_valid(const Outcome& o, const test::TempDir& dir) {
  expect_valid(o.tripinfo, "tripinfo_file.xsd", dir);
  expect_valid(o.summary, "summary_file.xsd", dir);
  expect_valid(o.fcd, "fcd_file.xsd", dir);
  expect_valid(o.edgedata, "meandata_file.xsd", dir);
  expect_valid(sumo_side_path(o.tripinfo.string()), "tripinfo_file.xsd", dir);
  expect_valid(sumo_side_path(o.summary.string()), "summary_file.xsd", dir);
  expect_valid(sumo_side_path(o.fcd.string()), "fcd_file.xsd", dir);
  expect_valid(sumo_side_path(o.edgedata.string()), "meandata_file.xsd", dir);
}

// One line per trip, each vehicle once, durations that are arrival - depart.
std::vector<SumoTripPiece> expect_one_line_per_trip(const fs::path& tripinfo, uint64_t trips) {
  const std::vector<SumoTripPiece> lines = read_sumo_tripinfo(tripinfo.string());
  EXPECT_EQ(lines.size(), trips);
  std::set<std::string> ids;
  for (const SumoTripPiece& t : lines) {
    EXPECT_TRUE(ids.insert(t.id).second) << t.id << " has two lines";
    EXPECT_NE(t.vaporized, "traci") << t.id;
    EXPECT_GT(t.route_length, 0.0) << t.id;
    EXPECT_GE(t.arrival, t.depart) << t.id;
  }
  return lines;
}

double mean_duration(const std::vector<SumoTripPiece>& lines) {
  double sum = 0;
  for (const SumoTripPiece& t : lines) sum += t.arrival - t.depart;
  return lines.empty() ? 0 : sum / static_cast<double>(lines.size());
}

// edge id -> sampledSeconds, as written, of an edgeData file's intervals.
std::map<std::string, std::string> sampled_seconds(const fs::path& file) {
  std::map<std::string, std::string> out;
  XmlStream xml(file.string());
  for (XmlStream::Event e = xml.next(); e != XmlStream::Event::Eof; e = xml.next())
    if (e == XmlStream::Event::Start && xml.name() == "edge")
      out[xml.required("id")] = xml.get("sampledSeconds", "");
  return out;
}

class GridCorridorTest : public ::testing::TestWithParam<SumoMode> {};

TEST_P(GridCorridorTest, HandsVehiclesBothWaysLosesNoneAndWritesOneTripinfoLinePerTrip) {
  test::TempDir dir("cosim_grid");
  const Outcome o = run_case(Case(kGrid, kGridCorridor, GetParam()), dir);
  // Every vehicle arrived, in one of the two.
  EXPECT_EQ(o.last.loaded, 1000u);
  EXPECT_EQ(o.last.arrived, 1000u);
  EXPECT_EQ(o.last.in_sumo + o.last.in_handover + o.last.in_lpsim, 0u);
  EXPECT_GT(o.report.into_sumo, 200u);
  EXPECT_GT(o.report.out_of_sumo, 100u);
  EXPECT_GT(o.report.arrived_in_sumo, 50u);
  EXPECT_EQ(o.report.into_sumo, o.report.out_of_sumo + o.report.arrived_in_sumo);
  EXPECT_GT(o.most_in_sumo, 5u);
  const std::vector<SumoTripPiece> lines = expect_one_line_per_trip(o.tripinfo, 1000);
  EXPECT_EQ(o.lpsim_arrived, 1000u);
  // The whole trips, against SUMO alone on the same files.
  EXPECT_NEAR(mean_duration(lines), reference_value(kGrid, "sumo_mean_duration_s"),
              0.10 * reference_value(kGrid, "sumo_mean_duration_s"));
  double length = 0;
  for (const SumoTripPiece& t : lines) length += t.route_length;
  EXPECT_NEAR(length / 1000.0, reference_value(kGrid, "sumo_mean_route_length_m"), 10.0);
  expect_outputs_valid(o, dir);
  // One edgeData: the corridor's edges as SUMO measured them, the others as LPSim did.
  const auto merged = sampled_seconds(o.edgedata),
             sumo = sampled_seconds(sumo_side_path(o.edgedata.string()));
  for (const std::string& e : kGridCorridor) EXPECT_EQ(merged.at(e), sumo.at(e)) << e;
  EXPECT_EQ(merged.size(), 80u);
  for (const char* outside : {"A0A1", "E4D4", "B1C1"})
    EXPECT_NE(merged.at(outside), sumo.count(outside) ? sumo.at(outside) : "") << outside;
}

INSTANTIATE_TEST_SUITE_P(Modes, GridCorridorTest, ::testing::Values(SumoMode::Libsumo, SumoMode::Traci),
                         [](const auto& info) {
                           return info.param == SumoMode::Libsumo ? "Libsumo" : "Traci";
                         });

TEST(CosimulationTest, InProcessAndOverTraciGiveTheSameTrips) {
  test::TempDir a("cosim_lib"), b("cosim_traci");
  const Outcome in_process = run_case(Case(kGrid, kGridCorridor, SumoMode::Libsumo), a);
  const Outcome traci = run_case(Case(kGrid, kGridCorridor, SumoMode::Traci), b);
  EXPECT_EQ(read_all(in_process.tripinfo), read_all(traci.tripinfo));
  EXPECT_EQ(in_process.report.into_sumo, traci.report.into_sumo);
}

TEST(CosimulationTest, QueueDownstreamInLpsimHoldsVehiclesInSumo) {
  test::TempDir dir("cosim_down");
  // The corridor is BC; the red light at D queues LPSim's CD full, back to C.
  const Outcome o = run_case(Case(kLine, {"BC"}), dir);
  EXPECT_EQ(o.last.arrived, 150u);
  EXPECT_EQ(o.report.into_sumo, 150u);
  EXPECT_EQ(o.report.out_of_sumo, 150u);
  EXPECT_GT(o.report.held, 20u);  // LPSim had no room at CD's start: held at SUMO's exit
  EXPECT_GT(o.report.longest_boundary_wait, 20.0);
  EXPECT_GT(o.most_in_sumo, 30u);  // the queue reached back into SUMO's BC
  expect_one_line_per_trip(o.tripinfo, 150);
  expect_outputs_valid(o, dir);
}

TEST(CosimulationTest, QueueInSumoSpillsBackIntoLpsim) {
  test::TempDir dir("cosim_up");
  // The corridor is CD, ending at the red light: SUMO's queue fills CD and LPSim's vehicles on BC stand at
  // its end behind the mirrored ones (or behind a vehicle SUMO has not inserted yet).
  Case c(kLine, {"CD"});
  c.watch_lane = "BC_0";
  const Outcome o = run_case(c, dir);
  EXPECT_EQ(o.last.arrived, 150u);
  EXPECT_EQ(o.report.into_sumo, 150u);
  EXPECT_EQ(o.report.out_of_sumo, 150u);
  EXPECT_GT(o.steps_lpsim_queued_at_boundary, 100);
  EXPECT_GT(o.most_in_sumo, 40u);
  const std::vector<SumoTripPiece> lines = expect_one_line_per_trip(o.tripinfo, 150);
  // The light and its queue are SUMO's: the trips take about as long as in SUMO alone.
  EXPECT_NEAR(mean_duration(lines), reference_value(kLine, "sumo_mean_duration_s"),
              0.10 * reference_value(kLine, "sumo_mean_duration_s"));
  expect_outputs_valid(o, dir);
}

TEST(CosimulationTest, RoutesCrossingTheCorridorTwiceAreHandedOverTwice) {
  test::TempDir dir("cosim_twice");
  // Zig-zags through the grid: onto the middle row, off it, onto it again further east, off it again.
  const std::string routes = dir.write("twice.rou.xml", R"(<routes>
    <route id="z1" edges="A3A2 A2B2 B2B3 B3C3 C3C2 C2D2 D2D1"/>
    <route id="z2" edges="E1E2 E2D2 D2D1 D1C1 C1C2 C2B2 B2B3"/>
    <flow id="twice1" route="z1" begin="0" end="300" period="15"/>
    <flow id="twice2" route="z2" begin="5" end="300" period="15"/>
</routes>
)");
  Case c(kGrid, kGridCorridor);
  c.extra_args = {"-r", routes};
  const Outcome o = run_case(c, dir);
  EXPECT_EQ(o.last.arrived, o.last.loaded);
  int twice = 0;
  for (const auto& [id, n] : o.hand_ins) {
    EXPECT_EQ(n, 2) << id;
    twice += n == 2;
  }
  EXPECT_EQ(twice, 40);
  expect_outputs_valid(o, dir);
  const std::vector<SumoTripPiece> lines = expect_one_line_per_trip(o.tripinfo, o.last.loaded);
  // Each trip's length is its whole route's, as LPSim alone measures it: the pieces add up.
  const test::CliResult alone = test::run_lpsim(
      dir.path(), {"run", "-c", kGrid, "-r", routes, "--tripinfo-output", "alone.xml", "--no-step-log"});
  ASSERT_EQ(alone.exit_code, 0) << alone.err;
  std::map<std::string, double> length;
  for (const SumoTripPiece& t : read_sumo_tripinfo((dir.path() / "alone.xml").string()))
    length[t.id] = t.route_length;
  for (const SumoTripPiece& t : lines)
    EXPECT_NEAR(t.route_length, length.at(t.id), 0.02 * length.at(t.id)) << t.id;
}

TEST(CosimulationTest, SumoStepsOfHalfLpsimsAreCoupledEverySecond) {
  test::TempDir dir("cosim_half");
  Case c(kLine, {"CD"});
  c.sumo_args = {"--step-length", "0.5"};
  const Outcome o = run_case(c, dir);
  EXPECT_DOUBLE_EQ(o.report.period, 1.0);
  EXPECT_EQ(o.last.arrived, 150u);
  expect_one_line_per_trip(o.tripinfo, 150);
  expect_outputs_valid(o, dir);
}

TEST(CosimulationTest, StepLengthsWithoutAShortCommonMultipleAreRefused) {
  test::TempDir dir("cosim_steps");
  try {
    Case c(kLine, {"CD"});
    c.sumo_args = {"--step-length", "0.999"};
    run_case(c, dir);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("step length 0.999"), std::string::npos) << e.what();
  }
}

// The <tripinfo .../> lines of a tripinfo output by vehicle id.
std::map<std::string, std::string> trips_by_id(const fs::path& file) {
  const std::string text = read_all(file);
  static const std::regex line("<tripinfo id=\"([^\"]+)\"[^\n]*");
  std::map<std::string, std::string> out;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), line); it != std::sregex_iterator(); ++it)
    out[(*it)[1]] = it->str();
  return out;
}

// SUMO killed: one error, LPSim's outputs well-formed, and the trips that ended before, those that visited
// SUMO among them, in the tripinfo as the uninterrupted run has them (before, only the trips that never
// visited SUMO were kept: 77 of 204 in a command-line run). A trip whose piece SUMO had not yet written when
// it died is left out rather than written short.
TEST(CosimulationTest, SumoKilledMidRunIsOneErrorAndTheEndedTripsAreWritten) {
  test::TempDir whole_dir("cosim_whole");
  Case c{kGrid, kGridCorridor, SumoMode::Traci};
  run_case(c, whole_dir);
  test::TempDir dir("cosim_kill");
  c.kill_sumo_after = 600;
  try {
    run_case(c, dir);
    FAIL() << "no error";
  } catch (const SumoError& e) {
    EXPECT_NE(std::string(e.what()).find("ended (status 137)"), std::string::npos) << e.what();
  }
  const std::map<std::string, std::string> whole = trips_by_id(fs::path(whole_dir.path()) / "tripinfo.xml");
  const std::map<std::string, std::string> cut = trips_by_id(fs::path(dir.path()) / "tripinfo.xml");
  int ended_before = 0, visited = 0;
  static const std::regex arrival(" arrival=\"([0-9.]+)\"");
  for (const auto& [id, line] : whole) {
    std::smatch m;
    ASSERT_TRUE(std::regex_search(line, m, arrival)) << line;
    if (std::stod(m[1]) < 595) ++ended_before;
  }
  for (const auto& [id, line] : cut) {
    ASSERT_TRUE(whole.count(id)) << id;
    EXPECT_EQ(line, whole.at(id));
  }
  const std::map<std::string, std::string> sumo_pieces =
      trips_by_id(sumo_side_path((fs::path(dir.path()) / "tripinfo.xml").string()));
  for (const auto& [id, line] : cut) visited += sumo_pieces.count(id) ? 1 : 0;
  EXPECT_GT(visited, 0) << "no trip that visited SUMO kept";
  EXPECT_GE(static_cast<double>(cut.size()), 0.9 * ended_before) << cut.size() << " of " << ended_before;
  if (std::system("xmllint --version > /dev/null 2>&1") != 0) GTEST_SKIP() << "xmllint not installed";
  for (const char* f : {"tripinfo.xml", "summary.xml", "fcd.xml", "edgedata.xml"}) {
    const std::string cmd = "xmllint --noout " + (fs::path(dir.path()) / f).string();
    EXPECT_EQ(std::system(cmd.c_str()), 0) << f;
  }
}

TEST(CosimulationCliTest, RunsWithACorridorFileAndRefusesUnknownEdgesWithFileAndLine) {
  test::TempDir dir("cosim_cli");
  const std::string corridor = dir.write("corridor.txt", "edge:A2B2\nedge:B2C2\njunction:B2\njunction:C2\n");
  const test::CliResult ok =
      test::run_lpsim(dir.path(), {"cosim", "-c", kGrid, "--corridor", corridor, "--tripinfo-output",
                                   "ti.xml", "--edgedata-output", "ed.xml", "--no-step-log", "--end", "400",
                                   "--sumo-args", "--no-warnings true"});
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_NE(ok.out.find("Handed into SUMO: "), std::string::npos) << ok.out;
  // The selection's junctions are named, not silently dropped.
  EXPECT_NE(ok.err.find("left out what is not a road (2 junction)"), std::string::npos) << ok.err;
  // Outputs named relative to the working folder: SUMO's side lands beside LPSim's.
  for (const char* f : {"ti.xml", "sumo.ti.xml", "ed.xml", "sumo.ed.xml"})
    EXPECT_TRUE(fs::exists(fs::path(dir.path()) / f)) << f;
  const std::string bad = dir.write("bad.txt", "edge:A2B2\nedge:nowhere\n");
  const test::CliResult r =
      test::run_lpsim(dir.path(), {"cosim", "-c", kGrid, "--corridor", bad, "--tripinfo-output", "t2.xml"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("bad.txt:2"), std::string::npos) << r.err;
  const test::CliResult none = test::run_lpsim(dir.path(), {"cosim", "-c", kGrid});
  EXPECT_EQ(none.exit_code, 2);
  EXPECT_NE(none.err.find("--corridor"), std::string::npos) << none.err;
  // SUMO told to wait for TraCI clients would wait for ever, unfinished trips are not merged: refused before
  // any output exists (LPSim's own --tripinfo-output.write-unfinished ended in a segmentation fault).
  const test::CliResult unfinished =
      test::run_lpsim(dir.path(), {"cosim", "-c", kGrid, "--corridor", corridor, "--tripinfo-output",
                                   "t3.xml", "--tripinfo-output.write-unfinished", "true"});
  EXPECT_EQ(unfinished.exit_code, 2) << unfinished.err;
  EXPECT_NE(unfinished.err.find("unfinished ones are not merged"), std::string::npos) << unfinished.err;
  EXPECT_FALSE(fs::exists(fs::path(dir.path()) / "t3.xml"));
  for (const char* waits :
       {"--remote-port 8813", "--num-clients=2", "--tripinfo-output.write-unfinished true"}) {
    const test::CliResult hang = test::run_lpsim(
        dir.path(),
        {"cosim", "-c", kGrid, "--corridor", corridor, "--tripinfo-output", "t3.xml", "--sumo-args", waits});
    EXPECT_EQ(hang.exit_code, 2) << waits;
    EXPECT_NE(hang.err.find("--sumo-args: --"), std::string::npos) << hang.err;
    EXPECT_FALSE(fs::exists(fs::path(dir.path()) / "t3.xml")) << waits;
  }
  // A snapshot has no SUMO files for SUMO to load: refused before the outputs are created (before, an
  // existing tripinfo was emptied first).
  const test::CliResult snap = test::run_lpsim(dir.path(), {"convert", "-c", kGrid, "-o", "g.lpsim"});
  ASSERT_EQ(snap.exit_code, 0) << snap.err;
  dir.write("kept.xml", "keep me\n");
  const test::CliResult from_snapshot = test::run_lpsim(
      dir.path(), {"cosim", "g.lpsim", "--corridor", corridor, "--tripinfo-output", "kept.xml"});
  EXPECT_EQ(from_snapshot.exit_code, 2);
  EXPECT_NE(from_snapshot.err.find("not a snapshot"), std::string::npos) << from_snapshot.err;
  EXPECT_EQ(test::read_file(fs::path(dir.path()) / "kept.xml"), "keep me\n");
  const test::CliResult zero =
      test::run_lpsim(dir.path(), {"cosim", "-c", kGrid, "--corridor", corridor, "--sumo-timeout", "0"});
  EXPECT_EQ(zero.exit_code, 2);
  EXPECT_NE(zero.err.find("expected a time > 0"), std::string::npos) << zero.err;
}

// SUMO's side of every output (sumo.<name>) is an output like the others: checked against the inputs, the
// other outputs and each other before anything is written, and so are the files --sumo-args names (SUMO
// writes them under the same prefix). Additional files given in --sumo-args join the co-simulation's own.
TEST(CosimulationCliTest, SumosSideOutputsAreCheckedAndItsAdditionalFilesAdded) {
  test::TempDir dir("cosim_side");
  const fs::path grid_dir = fs::path(kGrid).parent_path();
  fs::copy_file(grid_dir / "grid_tls.net.xml", fs::path(dir.path()) / "sumo.net.xml");
  fs::copy_file(grid_dir / "grid_tls.rou.xml", fs::path(dir.path()) / "sumo.rou.xml");
  const std::string net_before = test::read_file(fs::path(dir.path()) / "sumo.net.xml");
  const std::string corridor = dir.write("corridor.txt", "edge:A2B2\nedge:B2C2\n");
  auto refused = [&](std::vector<std::string> args, const std::string& says) {
    const test::CliResult r = test::run_lpsim(dir.path(), args);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find(says), std::string::npos) << r.err;
  };
  const std::vector<std::string> base{"cosim",      "-n",     "sumo.net.xml", "-r",  "sumo.rou.xml",
                                      "--corridor", corridor, "--end",        "100", "--no-step-log"};
  auto with = [&](std::vector<std::string> more) {
    std::vector<std::string> all = base;
    all.insert(all.end(), more.begin(), more.end());
    return all;
  };
  // SUMO would write sumo.net.xml and sumo.rou.xml over the scenario's own files.
  refused(with({"--fcd-output", "rou.xml", "--tripinfo-output", "net.xml"}), "SUMO's side of --");
  EXPECT_EQ(test::read_file(fs::path(dir.path()) / "sumo.net.xml"), net_before);
  // SUMO's side of the tripinfo would be the summary.
  refused(with({"--tripinfo-output", "ti.xml", "--summary-output", "sumo.ti.xml"}),
          "output SUMO's side of --tripinfo-output 'sumo.ti.xml'");
  // A file --sumo-args names lands under the prefix, and is checked there.
  refused(with({"--tripinfo-output", "sumo.q.xml", "--sumo-args", "--queue-output q.xml"}),
          "SUMO's --queue-output in --sumo-args");
  EXPECT_FALSE(fs::exists(fs::path(dir.path()) / "ti.xml"));

  dir.write("extra.add.xml", "<additional>\n    <edgeData id=\"x\" file=\"extra_ed.xml\"/>\n</additional>\n");
  const test::CliResult ok = test::run_lpsim(dir.path(), with({"--edgedata-output", "ed.xml", "--sumo-args",
                                                               "-a extra.add.xml --no-warnings true"}));
  ASSERT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_TRUE(fs::exists(fs::path(dir.path()) / "sumo.extra_ed.xml"));  // the user's
  EXPECT_TRUE(fs::exists(fs::path(dir.path()) / "sumo.ed.xml"));        // the co-simulation's own
  EXPECT_EQ(test::read_file(fs::path(dir.path()) / "sumo.net.xml"), net_before);
}

// The summary, the statistics and the report of a co-simulation count the vehicles on both sides: SUMO's
// insertions of trips that depart in the corridor, its running vehicles and its arrivals. Before, a corridor
// of the whole network reported inserted="0" beside 1000 trips, and at --end 400 the summary said 204
// arrived where the tripinfo held 269.
TEST(CosimulationCliTest, SummaryAndStatisticsCountBothSides) {
  test::TempDir dir("cosim_counts");
  std::string all;
  const std::string net = read_all(fs::path(kGrid).parent_path() / "grid_tls.net.xml");
  static const std::regex edge("<edge id=\"([A-Z0-9]+)\"");
  for (auto it = std::sregex_iterator(net.begin(), net.end(), edge); it != std::sregex_iterator(); ++it)
    all += "edge:" + (*it)[1].str() + "\n";
  const std::string whole = dir.write("all.txt", all);
  const std::string row = dir.write("row.txt", "edge:A2B2\nedge:B2C2\n");
  auto last_summary = [&](const char* file, const char* attr) {
    const std::string text = read_all(fs::path(dir.path()) / file);
    const std::regex re(std::string(" ") + attr + "=\"([0-9]+)\"");
    long long last = -1;
    for (auto it = std::sregex_iterator(text.begin(), text.end(), re); it != std::sregex_iterator(); ++it)
      last = std::stoll((*it)[1]);
    return last;
  };
  auto trips = [&](const char* file) {
    const std::string text = read_all(fs::path(dir.path()) / file);
    long long n = 0;
    for (size_t at = text.find("<tripinfo "); at != std::string::npos; at = text.find("<tripinfo ", at + 1))
      ++n;
    return n;
  };
  const test::CliResult a = test::run_lpsim(
      dir.path(), {"cosim", "-c", kGrid, "--corridor", whole, "--tripinfo-output", "ta.xml",
                   "--summary-output", "sa.xml", "--statistic-output", "st.xml", "--no-step-log"});
  ASSERT_EQ(a.exit_code, 0) << a.err;
  EXPECT_EQ(last_summary("sa.xml", "inserted"), 1000);
  EXPECT_EQ(last_summary("sa.xml", "arrived"), 1000);
  EXPECT_EQ(trips("ta.xml"), 1000);
  EXPECT_NE(read_all(fs::path(dir.path()) / "st.xml").find("<vehicles loaded=\"1000\" inserted=\"1000\""),
            std::string::npos);
  EXPECT_NE(a.out.find("Inserted: 1000 (Loaded: 1000)"), std::string::npos) << a.out;
  const test::CliResult b =
      test::run_lpsim(dir.path(), {"cosim", "-c", kGrid, "--corridor", row, "--tripinfo-output", "tb.xml",
                                   "--summary-output", "sb.xml", "--end", "400", "--no-step-log"});
  ASSERT_EQ(b.exit_code, 0) << b.err;
  EXPECT_EQ(last_summary("sb.xml", "arrived"), trips("tb.xml"));
}

// A trip that ends in the corridor ends at its arrivalPos there, as SUMO alone ends it (before, SUMO was not
// told, and the trip ran to the lane's end: 179.2 m).
TEST(CosimulationCliTest, ArrivalPosOnACorridorEdgeIsHonoured) {
  test::TempDir dir("cosim_arrival_pos");
  const std::string net = (fs::path(kGrid).parent_path() / "grid_tls.net.xml").string();
  dir.write("ap.rou.xml",
            "<routes>\n    <vehicle id=\"v\" depart=\"0\" arrivalPos=\"20\"><route edges=\"A1A2 "
            "A2B2\"/></vehicle>\n"
            "    <vehicle id=\"w\" depart=\"5\"><route edges=\"A1A2 A2B2\"/></vehicle>\n</routes>\n");
  const std::string corridor = dir.write("corridor.txt", "edge:A2B2\n");
  const test::CliResult r =
      test::run_lpsim(dir.path(), {"cosim", "-n", net, "-r", "ap.rou.xml", "--corridor", corridor,
                                   "--tripinfo-output", "t.xml", "--no-step-log"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::map<std::string, std::string> trips = trips_by_id(fs::path(dir.path()) / "t.xml");
  ASSERT_EQ(trips.size(), 2u);
  static const std::regex pos(" arrivalPos=\"([0-9.]+)\"");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(trips.at("v"), m, pos));
  EXPECT_GE(std::stod(m[1]), 20.0);
  EXPECT_LT(std::stod(m[1]), 25.0);
  ASSERT_TRUE(std::regex_search(trips.at("w"), m, pos));
  EXPECT_GT(std::stod(m[1]), 150.0);  // no arrivalPos: the lane's end
}

// A bus's scheduled stop on a corridor edge is made in SUMO, the others in LPSim: its stop time is all three
// stops' 60 s, as in LPSim alone (before, SUMO drove past the corridor's stop: 40 s).
TEST(CosimulationCliTest, ScheduledStopsOnCorridorEdgesAreMadeInSumo) {
  test::TempDir dir("cosim_stops");
  const std::string net = (fs::path(kGrid).parent_path() / "grid_tls.net.xml").string();
  dir.write("bus.rou.xml",
            "<routes>\n    <vType id=\"bus\" vClass=\"bus\" length=\"12\"/>\n"
            "    <vehicle id=\"b\" type=\"bus\" depart=\"0\"><route edges=\"A1A2 A2B2 B2C2 C2D2\"/>\n"
            "        <stop lane=\"A1A2_0\" endPos=\"100\" duration=\"20\"/>\n"
            "        <stop lane=\"B2C2_0\" endPos=\"120\" duration=\"20\"/>\n"
            "        <stop lane=\"C2D2_0\" endPos=\"100\" duration=\"20\"/>\n"
            "    </vehicle>\n</routes>\n");
  const std::string corridor = dir.write("corridor.txt", "edge:B2C2\n");
  const test::CliResult co =
      test::run_lpsim(dir.path(), {"cosim", "-n", net, "-r", "bus.rou.xml", "--corridor", corridor,
                                   "--tripinfo-output", "co.xml", "--no-step-log"});
  ASSERT_EQ(co.exit_code, 0) << co.err;
  const test::CliResult alone = test::run_lpsim(
      dir.path(), {"run", "-n", net, "-r", "bus.rou.xml", "--tripinfo-output", "alone.xml", "--no-step-log"});
  ASSERT_EQ(alone.exit_code, 0) << alone.err;
  static const std::regex stop_time(" stopTime=\"([0-9.]+)\"");
  std::smatch m;
  const std::string co_trip = trips_by_id(fs::path(dir.path()) / "co.xml").at("b");
  ASSERT_TRUE(std::regex_search(co_trip, m, stop_time)) << co_trip;
  EXPECT_DOUBLE_EQ(std::stod(m[1]), 60.0);
  const std::string sumo_piece =
      trips_by_id(sumo_side_path((fs::path(dir.path()) / "co.xml").string())).at("b");
  ASSERT_TRUE(std::regex_search(sumo_piece, m, stop_time)) << sumo_piece;
  EXPECT_DOUBLE_EQ(std::stod(m[1]), 20.0);  // the corridor's stop, made by SUMO
  const std::string alone_trip = trips_by_id(fs::path(dir.path()) / "alone.xml").at("b");
  ASSERT_TRUE(std::regex_search(alone_trip, m, stop_time)) << alone_trip;
  EXPECT_DOUBLE_EQ(std::stod(m[1]), 60.0);
}

// A trip that departs in the corridor departs in SUMO at the time it is due, as in LPSim alone and SUMO
// alone, with LPSim's step as long as SUMO's and half of it. Before, SUMO was told "now", its own clock one
// step behind LPSim's: 198 of grid_tls's 1000 trips departed a step before their time.
TEST(CosimulationCliTest, TripsDepartingInTheCorridorDepartWhenDue) {
  test::TempDir dir("cosim_depart");
  const std::string corridor = dir.write(
      "row.txt", "edge:A2B2\nedge:B2C2\nedge:C2D2\nedge:D2E2\nedge:E2D2\nedge:D2C2\nedge:C2B2\nedge:B2A2\n");
  const std::string routes = read_all(fs::path(kGrid).parent_path() / "grid_tls.rou.xml");
  std::map<std::string, double> due;
  static const std::regex vehicle("<vehicle id=\"([^\"]+)\" depart=\"([0-9.]+)\"");
  for (auto it = std::sregex_iterator(routes.begin(), routes.end(), vehicle); it != std::sregex_iterator();
       ++it)
    due[(*it)[1]] = std::stod((*it)[2]);
  ASSERT_EQ(due.size(), 1000u);
  for (const char* step : {"1", "0.5"}) {
    const test::CliResult r =
        test::run_lpsim(dir.path(), {"cosim", "-c", kGrid, "--corridor", corridor, "--tripinfo-output",
                                     "t.xml", "--step-length", step, "--no-step-log"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::map<std::string, std::string> trips = trips_by_id(fs::path(dir.path()) / "t.xml");
    EXPECT_EQ(trips.size(), 1000u);
    int early = 0;
    static const std::regex depart(" depart=\"([0-9.]+)\"");
    for (const auto& [id, line] : trips) {
      std::smatch m;
      ASSERT_TRUE(std::regex_search(line, m, depart)) << line;
      early += std::stod(m[1]) < due.at(id) - 1e-9 ? 1 : 0;
    }
    EXPECT_EQ(early, 0) << "LPSim step " << step;
  }
}

// A signal while a SUMO process is still starting (a region's network takes minutes to load) ends the run at
// once: exit 128 + the signal, the outputs closed well-formed and empty, the SUMO process gone. Before, the
// start went on waiting for SUMO's port for up to 300 s. The "SUMO" here never opens its port.
TEST(CosimulationCliTest, ASignalWhileSumoStartsEndsTheRunAtOnce) {
  test::TempDir dir("cosim_start_signal");
  const std::string corridor = dir.write("corridor.txt", "edge:A2B2\nedge:B2C2\n");
  const std::string slow = dir.write("slow_sumo", "#!/bin/sh\nsleep 30\n");
  fs::permissions(slow, fs::perms::owner_all);
  test::SpawnedLpsim lpsim(dir.path(), {"cosim", "-c", kGrid, "--corridor", corridor, "--tripinfo-output",
                                        "ti.xml", "--sumo-binary", slow, "--no-step-log"});
  ASSERT_TRUE(lpsim.started());
  ASSERT_TRUE(lpsim.wait_until([&] { return lpsim.err().find("lpsim: corridor:") != std::string::npos; }, 10))
      << lpsim.err();
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  lpsim.send(SIGINT);
  const auto t0 = std::chrono::steady_clock::now();
  const int status = lpsim.wait_exit(5);
  ASSERT_NE(status, -1) << "still running 5 s after SIGINT";
  EXPECT_LT(std::chrono::steady_clock::now() - t0, std::chrono::seconds(2));
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 128 + SIGINT) << lpsim.err();
  EXPECT_NE(lpsim.err().find("lpsim: interrupted by SIGINT"), std::string::npos) << lpsim.err();
  const std::string trips = read_all(fs::path(dir.path()) / "ti.xml");
  EXPECT_NE(trips.find("</tripinfos>"), std::string::npos) << trips;
}

}  // namespace
}  // namespace lpsim

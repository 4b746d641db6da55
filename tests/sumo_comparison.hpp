#pragma once
// The real sumo and lpsim run on the same files, and the flows' trips read from their tripinfo outputs: what
// the tests that compare LPSim with SUMO (tests/sumo/) share.
#include <gtest/gtest.h>

#include <regex>
#include <string>
#include <vector>

#include "lpsim_cli.hpp"
#include "meandata_entries.hpp"
#include "temp_dir.hpp"

namespace lpsim::test {

/// Whether sumo and netconvert are installed (the tests against SUMO skip without them).
inline bool have_sumo_and_netconvert() { return have_sumo_tool("sumo") && have_sumo_tool("netconvert"); }

/// Runs netconvert in `dir` with `args`; a failure fails the test (call it through ASSERT_NO_FATAL_FAILURE).
inline void netconvert(const TempDir& dir, const std::vector<std::string>& args) {
  const CliResult r = run_program(dir.path(), {"netconvert"}, args);
  ASSERT_EQ(r.exit_code, 0) << r.err;
}

/// Copies bundled scenario `name` into `dir` and runs the real sumo and `lpsim run` on its .sumocfg with
/// car-following model `model` and seed 42, each writing its statistic output, tripinfo and a whole-run
/// laneData into <p>_stats.xml, <p>_trips.xml and <p>_lanes.xml, p = "s" (SUMO) or "l" (LPSim). `additional`:
/// the cfg's own add-files, which --additional-files replaces. A failed run fails the test (call it through
/// ASSERT_NO_FATAL_FAILURE).
inline void run_bundled_with_lane_data(const TempDir& dir, const std::string& name, const std::string& model,
                                       const std::string& additional = "") {
  copy_scenario(name, dir.path());
  auto args = [&](const std::string& p) {
    dir.write(p + ".add.xml", "<additional>\n  <laneData id=\"lanes\" file=\"" + p +
                                  "_lanes.xml\" excludeEmpty=\"true\"/>\n</additional>\n");
    return std::vector<std::string>{"-c",
                                    name + ".sumocfg",
                                    "--default.carfollowmodel",
                                    model,
                                    "--additional-files",
                                    (additional.empty() ? "" : additional + ",") + p + ".add.xml",
                                    "--statistic-output",
                                    p + "_stats.xml",
                                    "--tripinfo-output",
                                    p + "_trips.xml",
                                    "--seed",
                                    "42"};
  };
  std::vector<std::string> sumo_args = args("s");
  sumo_args.push_back("--no-step-log");
  const CliResult sumo = run_program(dir.path(), {"sumo"}, sumo_args);
  ASSERT_EQ(sumo.exit_code, 0) << sumo.err;
  std::vector<std::string> lpsim_args = args("l");
  lpsim_args.insert(lpsim_args.begin(), "run");
  const CliResult lpsim = run_lpsim(dir.path(), lpsim_args);
  ASSERT_EQ(lpsim.exit_code, 0) << lpsim.err;
}

/// The vehicles inserted and the teleports of a statistic output (SUMO's or LPSim's); -1 where absent.
struct InsertedAndTeleports {
  int inserted = -1, teleports = -1;
};
inline InsertedAndTeleports inserted_and_teleports(const std::string& statistic) {
  InsertedAndTeleports c;
  std::smatch m;
  if (std::regex_search(statistic, m, std::regex(R"re(<vehicles [^>]*inserted="([0-9]+)")re")))
    c.inserted = std::stoi(m[1]);
  if (std::regex_search(statistic, m, std::regex(R"re(<teleports total="([0-9]+)")re")))
    c.teleports = std::stoi(m[1]);
  return c;
}

struct SumoAndLpsim {
  CliResult sumo, lpsim;
  std::string sumo_tripinfo, lpsim_tripinfo;  // their tripinfo outputs (s.xml, l.xml in the folder)
};

/// Runs `sumo` and `lpsim run` in `dir` with the same `args`, each writing its tripinfo output.
inline SumoAndLpsim run_sumo_and_lpsim(const TempDir& dir, const std::vector<std::string>& args) {
  SumoAndLpsim r;
  std::vector<std::string> sumo_args = args;
  sumo_args.insert(sumo_args.end(), {"--tripinfo-output", "s.xml", "--no-step-log"});
  r.sumo = run_program(dir.path(), {"sumo"}, sumo_args);
  std::vector<std::string> lpsim_args{"run"};
  lpsim_args.insert(lpsim_args.end(), args.begin(), args.end());
  lpsim_args.insert(lpsim_args.end(), {"--tripinfo-output", "l.xml"});
  r.lpsim = run_lpsim(dir.path(), lpsim_args);
  r.sumo_tripinfo = read_file(dir.path() / "s.xml");
  r.lpsim_tripinfo = read_file(dir.path() / "l.xml");
  return r;
}

struct FlowTrips {
  double mean_duration = 0;  // s; 0 without trips
  int count = 0;
};

/// The trips of flow `id` (vehicles "<id>.<n>") in a tripinfo output.
inline FlowTrips flow_trips(const std::string& tripinfo, const std::string& id) {
  const std::regex trip("<tripinfo id=\"" + id + R"re(\.[0-9]+"[^>]* duration="([0-9.]+)")re");
  double sum = 0;
  FlowTrips f;
  for (auto it = std::sregex_iterator(tripinfo.begin(), tripinfo.end(), trip); it != std::sregex_iterator();
       ++it, ++f.count)
    sum += std::stod((*it)[1]);
  if (f.count > 0) f.mean_duration = sum / f.count;
  return f;
}

/// The mean trip duration of flow `id`, expecting `count` trips of it.
inline double flow_mean_duration(const std::string& tripinfo, const std::string& id, int count) {
  const FlowTrips f = flow_trips(tripinfo, id);
  EXPECT_EQ(f.count, count) << id;
  return f.mean_duration;
}

struct Teleport {
  std::string id, cause;  // cause as SUMO words it: "jam", "yield", "wrong lane", "wrong lane, highway"
  double time;
};

/// The "Teleporting vehicle 'X'; waited too long (CAUSE), lane='L', time=T." warnings of a run's output, in
/// order (SUMO's and LPSim's words are the same).
inline std::vector<Teleport> teleports(const std::string& log) {
  const std::regex re(
      R"re(Teleporting vehicle '([^']+)'; waited too long \(([a-z ,]+)\), lane='[^']*', time=([0-9.]+))re");
  std::vector<Teleport> out;
  for (auto it = std::sregex_iterator(log.begin(), log.end(), re); it != std::sregex_iterator(); ++it)
    out.push_back(Teleport{(*it)[1], (*it)[2], std::stod((*it)[3])});
  return out;
}

}  // namespace lpsim::test

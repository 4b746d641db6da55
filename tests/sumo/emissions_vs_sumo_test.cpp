// Emissions edgeData and laneData against SUMO 1.15 itself, on the bundled scenarios emissions_free (cars
// accelerating and cruising), emissions_redlight (a queue at a red light restarting: a car, an HBEFA2 car and
// a bus) and emissions_classes (eight emission classes, HBEFA3 and HBEFA2): sumo and lpsim run each with its
// emissions.add.xml (edgeData every 60 s, laneData over the run with internal lanes). LPSim's trips are
// SUMO's there (arrivals equal, speeds second by second within 0.01 m/s, at the red light within 1 m/s), so
// every pollutant's mass, and the sampled seconds, of every edge and interval, and of every lane over the
// run, are within 2 % of SUMO's (where the speeds are SUMO's to 0.01 m/s, within 0.1 %). The outputs
// are valid against SUMO's meandata schema. Needs sumo (skipped without it).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <regex>
#include <string>
#include <utility>
#include <vector>

#include "lpsim_cli.hpp"
#include "meandata_entries.hpp"
#include "sumo_schema.hpp"
#include "temp_dir.hpp"

namespace lpsim {
namespace {

namespace fs = std::filesystem;

const char* const kCompared[] = {"sampledSeconds", "CO_abs",  "CO2_abs", "HC_abs",
                                 "PMx_abs",        "NOx_abs", "fuel_abs"};

struct EmissionCase {
  friend void PrintTo(const EmissionCase& c, std::ostream* os) { *os << c.scenario; }
  const char* scenario;
  double tolerance;        // relative, every entry and value
  double speed_tolerance;  // m/s: LPSim's FCD speeds against SUMO's
  bool internal_lanes;     // compare internal lanes too (their queue's restart differs at the red light)
};

// (vehicle, time) -> speed, from an FCD output.
std::map<std::pair<std::string, std::string>, double> fcd_speeds(const std::string& text) {
  std::map<std::pair<std::string, std::string>, double> out;
  static const std::regex tag(R"re(<timestep time="([^"]*)"|<vehicle id="([^"]*)"[^>]* speed="([^"]*)")re");
  std::string time;
  for (auto t = std::sregex_iterator(text.begin(), text.end(), tag); t != std::sregex_iterator(); ++t) {
    if ((*t)[1].matched)
      time = std::to_string(std::lround(std::stod((*t)[1]) * 1000));
    else
      out[{(*t)[2], time}] = std::stod((*t)[3]);
  }
  return out;
}

// (vehicle) -> arrival time, from a tripinfo output.
std::map<std::string, std::string> arrivals(const std::string& text) {
  std::map<std::string, std::string> out;
  static const std::regex trip(R"re(<tripinfo id="([^"]*)"[^>]* arrival="([^"]*)")re");
  for (auto t = std::sregex_iterator(text.begin(), text.end(), trip); t != std::sregex_iterator(); ++t)
    out[(*t)[1]] = std::to_string(std::stod((*t)[2]));
  return out;
}

class EmissionsVsSumoTest : public ::testing::TestWithParam<EmissionCase> {
 protected:
  void SetUp() override {
    if (!test::have_sumo_tool("sumo")) GTEST_SKIP() << "sumo not found";
  }

  // Runs `program` on the case's scenario in its own copy of it; what it wrote stays there.
  fs::path run(const std::vector<std::string>& program, const std::string& tag) {
    const std::string name = GetParam().scenario;
    const fs::path dir = tmp_.path() / tag;
    test::copy_scenario(name, dir);
    const test::CliResult r =
        test::run_program(dir, program,
                          {"-c", name + ".sumocfg", "-a", "emissions.add.xml", "--end", "240", "--fcd-output",
                           "fcd.xml", "--tripinfo-output", "tripinfo.xml", "--no-step-log"});
    EXPECT_EQ(r.exit_code, 0) << tag << ":\n" << r.out << r.err;
    return dir;
  }

  void expect_schema_valid(const fs::path& file) {
    const std::string schema = std::string(test::kSumoXsdDir) + "/meandata_file.xsd";
    if (std::system("xmllint --version > /dev/null 2>&1") != 0 || !fs::exists(schema)) return;
    const fs::path log = tmp_.path() / "xmllint.log";
    const std::string cmd = "xmllint --noout --schema " + test::usable_sumo_schema(schema, tmp_) + " " +
                            file.string() + " > " + log.string() + " 2>&1";
    EXPECT_EQ(std::system(cmd.c_str()), 0) << file << ":\n" << test::read_file(log);
  }

  // Every entry of SUMO's file is in LPSim's and agrees within the case's tolerance (values below 0.01 mg or
  // 0.01 s count as zero: what both write as "0" or 6-decimal noise). Returns the largest relative
  // difference.
  double compare(const std::string& file, const fs::path& sumo, const fs::path& lpsim) {
    const test::MeanDataEntries s = test::meandata_entries(test::read_file(sumo / file));
    const test::MeanDataEntries l = test::meandata_entries(test::read_file(lpsim / file));
    EXPECT_GT(s.size(), 3u) << file;
    EXPECT_EQ(s.size(), l.size()) << file;
    double worst = 0;
    for (const auto& [key, sumo_values] : s) {
      const std::string& id = std::get<2>(key);
      if (id[0] == ':' && !GetParam().internal_lanes) continue;
      const auto it = l.find(key);
      if (it == l.end()) {
        ADD_FAILURE() << file << ": no entry " << id << " [" << std::get<0>(key) << ", " << std::get<1>(key)
                      << ") in LPSim's output";
        continue;
      }
      for (const char* name : kCompared) {
        const double a = sumo_values.at(name), b = it->second.at(name);
        const double scale = std::max(std::abs(a), std::abs(b));
        const double diff = scale < 0.01 ? 0.0 : std::abs(a - b) / scale;
        worst = std::max(worst, diff);
        EXPECT_LE(diff, GetParam().tolerance)
            << file << " " << id << " [" << std::get<0>(key) << ", " << std::get<1>(key) << ") " << name
            << ": SUMO " << a << ", LPSim " << b;
      }
    }
    return worst;
  }

  test::TempDir tmp_{"lpsim_emissions_vs_sumo"};
};

TEST_P(EmissionsVsSumoTest, EdgeAndLaneEmissionsWithinToleranceOfSumo) {
  const fs::path sumo = run({"sumo"}, "sumo");
  const fs::path lpsim = run({LPSIM_BINARY, "run"}, "lpsim");

  // The trips first: where they differ, so do their emissions.
  EXPECT_EQ(arrivals(test::read_file(lpsim / "tripinfo.xml")),
            arrivals(test::read_file(sumo / "tripinfo.xml")));
  const auto s = fcd_speeds(test::read_file(sumo / "fcd.xml"));
  const auto l = fcd_speeds(test::read_file(lpsim / "fcd.xml"));
  EXPECT_EQ(s.size(), l.size());
  double speed_worst = 0;
  for (const auto& [key, speed] : s)
    if (auto it = l.find(key); it != l.end())
      speed_worst = std::max(speed_worst, std::abs(speed - it->second));
  EXPECT_LE(speed_worst, GetParam().speed_tolerance);

  const double edges = compare("edges_60.xml", sumo, lpsim);
  const double lanes = compare("lanes.xml", sumo, lpsim);
  RecordProperty("worst_edge_difference", std::to_string(edges));
  RecordProperty("worst_lane_difference", std::to_string(lanes));
  std::printf("%s: largest relative difference to SUMO: edges %.2e, lanes %.2e (speeds within %.2f m/s)\n",
              GetParam().scenario, edges, lanes, speed_worst);
  expect_schema_valid(lpsim / "edges_60.xml");
  expect_schema_valid(lpsim / "lanes.xml");
}

INSTANTIATE_TEST_SUITE_P(BundledScenarios, EmissionsVsSumoTest,
                         ::testing::Values(EmissionCase{"emissions_free", 1e-3, 0.01, true},
                                           EmissionCase{"emissions_classes", 1e-3, 0.01, true},
                                           EmissionCase{"emissions_redlight", 0.02, 1.0, false}),
                         [](const ::testing::TestParamInfo<EmissionCase>& info) {
                           return std::string(info.param.scenario);
                         });

}  // namespace
}  // namespace lpsim

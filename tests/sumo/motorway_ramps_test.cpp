// scenarios/motorway_ramps, run by the real sumo and by lpsim with each car-following model: a 3-lane
// motorway at 130 km/h, an on-ramp whose lane runs on for 300 m and alone leads to the off-ramp (a weaving
// section), then a lane drop; cars and trucks, step 0.5 s. Every lane of the motorway before the weaving
// section used to count as a best lane for the exiting vehicles (none of them leads onto the off-ramp's
// lane), so they reached the section on the far lanes, stood at its end side by side with the entering
// vehicles that needed their lanes and jammed the motorway (Krauss: 1,217 of 1,726 arrived, mean trip 633 s
// against SUMO's 123 s). Asserted: insertions, arrivals and teleports as SUMO's, the vehicles through the
// ramp's lane, the off-ramp and every edge as SUMO's, and the mean trip near SUMO's. How LPSim spreads the
// through traffic over the lanes differs from SUMO (docs/VALIDATION.md) and is not asserted.
#include <gtest/gtest.h>

#include <map>
#include <regex>
#include <string>

#include "lpsim_cli.hpp"
#include "meandata_entries.hpp"
#include "sumo_comparison.hpp"
#include "temp_dir.hpp"

namespace lpsim {
namespace {

using test::read_file;
using test::TempDir;

struct Totals {
  int inserted = -1, teleports = -1, arrived = 0;
  double mean_duration = 0;
  std::map<std::string, double> entered;  // per lane, and per edge under the edge's id
};

Totals read_totals(const TempDir& dir, const std::string& prefix) {
  Totals t;
  const test::InsertedAndTeleports c =
      test::inserted_and_teleports(read_file(dir.path() / (prefix + "_stats.xml")));
  t.inserted = c.inserted;
  t.teleports = c.teleports;
  const std::string trips = read_file(dir.path() / (prefix + "_trips.xml"));
  const std::regex duration(R"re(<tripinfo [^>]*duration="([0-9.]+)")re");
  double sum = 0;
  for (auto it = std::sregex_iterator(trips.begin(), trips.end(), duration); it != std::sregex_iterator();
       ++it, ++t.arrived)
    sum += std::stod((*it)[1]);
  if (t.arrived > 0) t.mean_duration = sum / t.arrived;
  for (const auto& [key, values] : test::meandata_entries(read_file(dir.path() / (prefix + "_lanes.xml")))) {
    const std::string& lane = std::get<2>(key);
    if (lane.empty() || lane[0] == ':') continue;
    const double entered = values.count("entered") ? values.at("entered") : 0.0;
    t.entered[lane] += entered;
    t.entered[lane.substr(0, lane.rfind('_'))] += entered;
  }
  return t;
}

class MotorwayRampsTest : public ::testing::TestWithParam<const char*> {
 protected:
  void SetUp() override {
    if (!test::have_sumo_tool("sumo")) GTEST_SKIP() << "sumo not found";
  }
};

TEST_P(MotorwayRampsTest, WeavesMergesAndDropsALaneAsSumo) {
  const std::string model = GetParam();
  TempDir dir("lpsim_motorway");
  ASSERT_NO_FATAL_FAILURE(test::run_bundled_with_lane_data(dir, "motorway_ramps", model));

  Totals s = read_totals(dir, "s"), l = read_totals(dir, "l");
  ASSERT_GT(s.inserted, 1700);
  EXPECT_EQ(l.inserted, s.inserted);
  EXPECT_EQ(l.arrived, s.arrived);
  EXPECT_EQ(s.teleports, 0);
  EXPECT_EQ(l.teleports, 0);
  // Every vehicle passes each edge on its route within the run, the exiting ones over the ramp's lane.
  for (const char* id : {"BC", "CO", "CD", "DE", "EF", "BC_0", "CO_0"})
    EXPECT_NEAR(l.entered[id], s.entered[id], 0.02 * s.entered[id]) << id;
  // Measured at e926eb2: +11 % (Krauss), +15 % (IDM): the through traffic slows where the dropped lane's
  // vehicles merge (docs/VALIDATION.md).
  EXPECT_NEAR(l.mean_duration, s.mean_duration, 0.2 * s.mean_duration);
}

INSTANTIATE_TEST_SUITE_P(BothModels, MotorwayRampsTest, ::testing::Values("Krauss", "IDM"),
                         [](const ::testing::TestParamInfo<const char*>& info) { return info.param; });

}  // namespace
}  // namespace lpsim

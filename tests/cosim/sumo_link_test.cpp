// SumoLink with the real SUMO, in process (libsumo) and as a sumo process over TraCI: it starts on a bundled
// network, takes a vehicle in on a given lane with a given speed and drives its route to the end, leaves a
// vehicle it cannot insert pending until removed, refuses an id in use, and fails to start with one error,
// quickly, when the binary or the network is missing; over TraCI a SUMO killed or stopped mid-run is one
// error, not a hang.
#include "sumo_bridge/sumo_link.hpp"

#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <chrono>
#include <string>
#include <vector>

namespace lpsim {
namespace {

const std::string kNet = std::string(LPSIM_SCENARIOS_DIR) + "/grid_tls/grid_tls.net.xml";

std::vector<std::string> sumo_args(const std::string& net = kNet) {
  return {"-n", net, "--begin", "0", "--step-length", "1", "--no-step-log", "true", "--no-warnings", "true"};
}

bool contains(const std::vector<std::string>& ids, const std::string& id) {
  return std::find(ids.begin(), ids.end(), id) != ids.end();
}

class SumoLinkTest : public ::testing::TestWithParam<SumoMode> {};

TEST_P(SumoLinkTest, TakesAVehicleInOnItsLaneWithItsSpeedAndDrivesItsRoute) {
  auto sumo = start_sumo(GetParam(), "sumo", sumo_args());
  EXPECT_EQ(sumo->mode(), GetParam());
  EXPECT_NE(sumo->version().find("1.15"), std::string::npos) << sumo->version();
  EXPECT_DOUBLE_EQ(sumo->step_length(), 1.0);
  SumoEntry v1{"v1", "DEFAULT_VEHTYPE", {"A0B0", "B0C0"}, 1, 0.0, 12.5};
  v1.speed_factor = 1.0;  // the lane's limit, 13.89 m/s, is then above its speed
  sumo->add(v1);
  sumo->step_to(1.0);
  EXPECT_DOUBLE_EQ(sumo->time(), 1.0);
  EXPECT_TRUE(sumo->pending().empty());
  const SumoVehicle v = sumo->vehicle("v1");
  EXPECT_EQ(v.edge, "A0B0");
  EXPECT_EQ(v.lane, 1);
  EXPECT_DOUBLE_EQ(v.pos, 0.0);  // inserted where it was put: it moves from the next step on
  EXPECT_DOUBLE_EQ(v.speed, 12.5);
  bool arrived = false;
  for (double t = 2; t <= 300 && !arrived; ++t) {
    sumo->step_to(t);
    arrived = contains(sumo->arrived(), "v1");
    if (arrived) break;
    // On its route, or inside a junction between its edges.
    const std::vector<std::string> on_route{"A0B0", ":B0_", "B0C0"};
    const std::string edge = sumo->vehicle("v1").edge;
    EXPECT_TRUE(std::any_of(on_route.begin(), on_route.end(), [&](const std::string& e) {
      return edge.compare(0, e.size(), e) == 0;
    })) << edge;
  }
  EXPECT_TRUE(arrived);
  sumo->close();
}

TEST_P(SumoLinkTest, AVehicleItCannotInsertStaysPendingUntilRemoved) {
  auto sumo = start_sumo(GetParam(), "sumo", sumo_args());
  // Two vehicles at the same spot: the second fails SUMO's insertion checks.
  sumo->add(SumoEntry{"first", "DEFAULT_VEHTYPE", {"A0B0"}, 0, 0.0, 0.0});
  sumo->add(SumoEntry{"second", "DEFAULT_VEHTYPE", {"A0B0"}, 0, 0.0, 0.0});
  sumo->step_to(1.0);
  EXPECT_EQ(sumo->pending(), std::vector<std::string>{"second"});
  EXPECT_EQ(sumo->vehicle("first").edge, "A0B0");
  sumo->remove("second");
  sumo->step_to(2.0);
  EXPECT_TRUE(sumo->pending().empty());
  EXPECT_THROW(sumo->add(SumoEntry{"first", "DEFAULT_VEHTYPE", {"A0B0"}, 0, 0.0, 0.0}), SumoError);
  EXPECT_THROW(sumo->add(SumoEntry{"third", "no_such_type", {"A0B0"}, 0, 0.0, 0.0}), SumoError);
}

TEST_P(SumoLinkTest, AMissingNetworkIsOneErrorNotAHang) {
  const auto t0 = std::chrono::steady_clock::now();
  try {
    start_sumo(GetParam(), "sumo", sumo_args("/nonexistent/net.xml"));
    FAIL() << "started";
  } catch (const SumoError& e) {
    EXPECT_NE(std::string(e.what()).find("SUMO"), std::string::npos) << e.what();
  }
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 30.0);
}

INSTANTIATE_TEST_SUITE_P(Modes, SumoLinkTest, ::testing::Values(SumoMode::Libsumo, SumoMode::Traci),
                         [](const auto& info) {
                           return info.param == SumoMode::Libsumo ? "libsumo" : "traci";
                         });

// Over TraCI a SUMO that dies mid-run is an error on the next call, and one that stops answering is killed
// after the answer timeout: never a hang.
TEST(SumoLinkFaultTest, ASumoKilledMidRunIsOneError) {
  auto sumo = start_sumo(SumoMode::Traci, "sumo", sumo_args());
  sumo->step_to(5.0);
  ASSERT_GT(sumo->process_id(), 0);
  ::kill(sumo->process_id(), SIGKILL);
  try {
    sumo->step_to(6.0);
    FAIL() << "stepped";
  } catch (const SumoError& e) {
    EXPECT_NE(std::string(e.what()).find("ended (status 137) during simulationStep"), std::string::npos)
        << e.what();
  }
}

TEST(SumoLinkFaultTest, ASumoThatStopsAnsweringIsKilledAfterTheTimeout) {
  auto sumo = start_sumo(SumoMode::Traci, "sumo", sumo_args(), 1.0);
  sumo->step_to(5.0);
  ::kill(sumo->process_id(), SIGSTOP);
  const auto t0 = std::chrono::steady_clock::now();
  try {
    sumo->step_to(6.0);
    FAIL() << "stepped";
  } catch (const SumoError& e) {
    EXPECT_NE(std::string(e.what()).find("did not answer simulationStep within 1 s"), std::string::npos)
        << e.what();
  }
  const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_GE(waited, 0.9);
  EXPECT_LT(waited, 10.0);
}

TEST(SumoLinkStartTest, AMissingBinaryIsOneError) {
  try {
    start_sumo(SumoMode::Traci, "no-such-sumo-binary", sumo_args());
    FAIL() << "started";
  } catch (const SumoError& e) {
    EXPECT_NE(std::string(e.what()).find("no-such-sumo-binary"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace lpsim

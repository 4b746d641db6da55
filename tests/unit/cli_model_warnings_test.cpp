// Settings that load but are not modelled get one warning each, never silence: carFollowModel other than
// IDM and Krauss (one line per model naming its vTypes, the default model included), laneChangeModel other
// than LC2013 (LPSim's lane changing stands in for it), signal programs of a type other than static (run as
// static: one line with the count and ids). An edgeData or laneData of SUMO's noise or amitran types is
// refused: LPSim writes traffic measures and emissions; "hbefa", SUMO's old name of emissions, warns as SUMO.
#include <gtest/gtest.h>

#include <string>

#include "cli_scenario_fixture.hpp"

namespace lpsim {
namespace {

using test::CliScenarioTest;
using test::expect_input_error;
using test::has_line;

using CliModelWarningsTest = CliScenarioTest;

TEST_F(CliModelWarningsTest, CarFollowModelsOtherThanIdmAndKraussWarnOncePerModel) {
  write_routes(
      "cf.rou.xml",
      "<vType id=\"k1\" carFollowModel=\"Krauss\"/>\n<vType id=\"w1\" carFollowModel=\"Wiedemann\"/>\n"
      "<vType id=\"w\">\n<carFollowing-Wiedemann/>\n</vType>\n<vType id=\"i\" carFollowModel=\"IDM\"/>\n"
      "<vType id=\"e\" carFollowModel=\"EIDM\"/>\n<vType id=\"plain\"/>");
  const auto r = info_with_routes("cf.rou.xml");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(has_line(r,
                       "lpsim: warning: carFollowModel 'Wiedemann' is not implemented, IDM is used instead "
                       "for 2 vTypes: 'w1', 'w'"))
      << r.err;
  EXPECT_TRUE(has_line(r,
                       "lpsim: warning: carFollowModel 'EIDM' is not implemented, IDM is used instead for 1 "
                       "vType: 'e'"))
      << r.err;
  EXPECT_EQ(test::lines_of(r.err).size(), 2u) << r.err;  // IDM, Krauss and SUMO's default say nothing
  EXPECT_NE(r.out.find("not implemented: carFollowModel 'Wiedemann'"), std::string::npos) << r.out;
}

// SUMO's --no-warnings silences these too.
TEST_F(CliModelWarningsTest, NoWarningsSilencesThem) {
  write_routes("cf.rou.xml", "<vType id=\"w1\" carFollowModel=\"Wiedemann\"/>");
  const std::vector<std::string> run_it{"run", "-n", test::kGridTlsNet, "-r", "cf.rou.xml", "--end", "10"};
  const auto warned = run(run_it);
  ASSERT_EQ(warned.exit_code, 0) << warned.err;
  EXPECT_NE(warned.err.find("lpsim: warning: carFollowModel 'Wiedemann' is not implemented"),
            std::string::npos)
      << warned.err;
  for (const char* flag : {"--no-warnings", "-W"}) {
    std::vector<std::string> args = run_it;
    args.push_back(flag);
    const auto r = run(args);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.err.find("warning"), std::string::npos) << flag << ": " << r.err;
  }
}

TEST_F(CliModelWarningsTest, DefaultCarFollowModelNamesTheVTypesThatTakeIt) {
  write_routes("cf.rou.xml", "<vType id=\"k\" carFollowModel=\"Krauss\"/>\n<vType id=\"plain\"/>");
  // Implemented defaults say nothing.
  for (const char* model : {"Krauss", "IDM"}) {
    const auto r =
        run({"info", "-n", test::kGridTlsNet, "-r", "cf.rou.xml", "--default.carfollowmodel", model});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.err, "") << model;
  }
  // Another default: one warning naming it and the vTypes that name no model.
  const auto r =
      run({"info", "-n", test::kGridTlsNet, "-r", "cf.rou.xml", "--default.carfollowmodel", "W99"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err,
            "lpsim: warning: carFollowModel 'W99' is not implemented, IDM is used instead for 1 vType: "
            "'plain'\n");
  // No vType at all: the default vType takes the default model.
  write_routes("none.rou.xml", "");
  const auto d =
      run({"info", "-n", test::kGridTlsNet, "-r", "none.rou.xml", "--default.carfollowmodel", "W99"});
  EXPECT_EQ(d.err,
            "lpsim: warning: carFollowModel 'W99' (--default.carfollowmodel) is not implemented, IDM is used "
            "instead for vTypes that name no model\n");
}

TEST_F(CliModelWarningsTest, LaneChangeModelsOtherThanLc2013Warn) {
  std::string types;
  for (int i = 0; i < 7; ++i)
    types += "<vType id=\"s" + std::to_string(i) + "\" laneChangeModel=\"SL2015\"/>\n";
  write_routes("lc.rou.xml", types + "<vType id=\"d\" laneChangeModel=\"LC2013\"/>");
  const auto r = info_with_routes("lc.rou.xml");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err,
            "lpsim: warning: laneChangeModel 'SL2015' is not implemented, LPSim's lane changing (in place of "
            "LC2013) is used instead for 7 vTypes: 's0', 's1', 's2', 's3', 's4' and 2 more\n");
}

TEST_F(CliModelWarningsTest, SignalTypesOtherThanStaticAndActuatedRunAsStaticWarnOnce) {
  write_grid_net_with("actuated.net.xml", "type=\"static\"", "type=\"actuated\"");
  const auto actuated = run({"info", "-n", "actuated.net.xml"});
  ASSERT_EQ(actuated.exit_code, 0) << actuated.err;
  EXPECT_EQ(actuated.err, "");
  write_grid_net_with("delay.net.xml", "type=\"static\"", "type=\"delay_based\"");
  const auto r = run({"info", "-n", "delay.net.xml"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(
      r.err,
      "lpsim: warning: signal programs of type delay_based (1) are not implemented, these traffic lights run "
      "their phases as static programs: 'A0'\n");
  // An add-file program of the same id replaces the net's, and its type is the one that runs.
  write("static.add.xml",
        "<additional>\n<tlLogic id=\"A0\" programID=\"1\" type=\"static\" offset=\"0\">\n"
        "<phase duration=\"40\" state=\"GGGG\"/>\n</tlLogic>\n</additional>\n");
  const auto replaced = run({"info", "-n", "delay.net.xml", "-a", "static.add.xml"});
  EXPECT_EQ(replaced.err, "") << replaced.err;
}

TEST_F(CliModelWarningsTest, ActuatedParametersNotImplementedWarn) {
  write_grid_net_with("actuated.net.xml", "type=\"static\"", "type=\"actuated\"");
  write("params.add.xml",
        "<additional>\n<tlLogic id=\"A0\" programID=\"1\" type=\"actuated\" offset=\"0\">\n"
        "<param key=\"max-gap\" value=\"2.5\"/>\n<param key=\"jam-threshold\" value=\"10\"/>\n"
        "<phase duration=\"40\" state=\"GGGG\" minDur=\"5\" maxDur=\"50\"/>\n</tlLogic>\n</additional>\n");
  const auto r = run({"info", "-n", "actuated.net.xml", "-a", "params.add.xml"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(
      r.err,
      "lpsim: warning: actuated signal parameters other than max-gap, detector-gap and passing-time are "
      "not implemented, SUMO's defaults are used instead of 'jam-threshold' of 'A0'\n");
  write("bad.add.xml",
        "<additional>\n<tlLogic id=\"A0\" programID=\"1\" type=\"actuated\" offset=\"0\">\n"
        "<param key=\"max-gap\" value=\"soon\"/>\n"
        "<phase duration=\"40\" state=\"GGGG\" minDur=\"5\" maxDur=\"50\"/>\n</tlLogic>\n</additional>\n");
  expect_input_error(run({"info", "-n", "actuated.net.xml", "-a", "bad.add.xml"}), "bad.add.xml:2",
                     {"tlLogic 'A0' param 'max-gap'", "'soon'"});
}

TEST_F(CliModelWarningsTest, NoiseAndAmitranEdgeDataAreRefused) {
  for (const char* type : {"harmonoise", "amitran"}) {
    SCOPED_TRACE(type);
    write("data.add.xml",
          std::string("<additional>\n<!-- test input -->\n<laneData id=\"d\" file=\"o.xml\" type=\"") + type +
              "\"/>\n</additional>\n");
    expect_input_error(run({"info", "-n", test::kGridTlsNet, "-a", "data.add.xml"}), "data.add.xml:3",
                       {"<laneData id=\"d\">", std::string("type '") + type + "'", "not supported"});
  }
  write("data.add.xml",
        "<additional>\n<!-- test input -->\n<edgeData id=\"d\" file=\"o.xml\" type=\"bogus\"/>\n"
        "</additional>\n");
  expect_input_error(run({"info", "-n", test::kGridTlsNet, "-a", "data.add.xml"}), "data.add.xml:3",
                     {"unknown type 'bogus'"});
  write("data.add.xml",
        "<additional>\n<edgeData id=\"d\" file=\"o.xml\" type=\"traffic\"/>\n</additional>\n");
  EXPECT_EQ(run({"info", "-n", test::kGridTlsNet, "-a", "data.add.xml"}).exit_code, 0);
  write("data.add.xml",
        "<additional>\n<edgeData id=\"d\" file=\"o.xml\" type=\"emissions\"/>\n</additional>\n");
  const auto emissions = run({"info", "-n", test::kGridTlsNet, "-a", "data.add.xml"});
  EXPECT_EQ(emissions.exit_code, 0) << emissions.err;
  EXPECT_TRUE(emissions.err.empty()) << emissions.err;
}

TEST_F(CliModelWarningsTest, HbefaEdgeDataIsEmissionsWithSumosWarning) {
  write("data.add.xml",
        "<additional>\n<laneData id=\"old\" file=\"o.xml\" type=\"hbefa\"/>\n</additional>\n");
  const auto r = run({"info", "-n", test::kGridTlsNet, "-a", "data.add.xml"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(has_line(r,
                       "lpsim: warning: laneData 'old' (data.add.xml:2): the type 'hbefa' is deprecated, "
                       "'emissions' is its name now"))
      << r.err;
}

}  // namespace
}  // namespace lpsim

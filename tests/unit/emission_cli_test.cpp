// Emission classes and emissions outputs as a user meets them: an emissionClass SUMO 1.15 does not know is an
// error naming the vType and its file:line; a class of a model LPSim does not implement (HBEFA4, PHEMlight,
// Energy, ...) loads, and is an error naming the vType, its file:line and the output only once an emissions
// output asks for it; --emissions.volumetric-fuel gives fuel in ml (by the fuel's density); a snapshot keeps
// what emissions need (the same outputs as from the XML files).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "cli_scenario_fixture.hpp"
#include "meandata_entries.hpp"

namespace lpsim {
namespace {

using test::CliScenarioTest;
using test::expect_input_error;

namespace fs = std::filesystem;

using EmissionCliTest = CliScenarioTest;

TEST_F(EmissionCliTest, UnknownEmissionClassIsAnErrorNamingTheVType) {
  write_routes("r.rou.xml", "<vType id=\"odd\" emissionClass=\"PC_G_EU4\"/>");
  expect_input_error(info_with_routes("r.rou.xml"), "r.rou.xml:3",
                     {"vType 'odd'", "emissionClass 'PC_G_EU4' does not exist"});
}

TEST_F(EmissionCliTest, UnimplementedModelIsRefusedOnlyWhenEmissionsAreAsked) {
  write_routes("r.rou.xml",
               "<vType id=\"h4\" emissionClass=\"HBEFA4/PC_petrol_Euro-4\"/>\n"
               "<vehicle id=\"v\" type=\"h4\" depart=\"0\"><route edges=\"A0A1 A1A2\"/></vehicle>");
  const auto plain = run({"run", "-n", test::kGridTlsNet, "-r", "r.rou.xml", "--no-step-log"});
  EXPECT_EQ(plain.exit_code, 0) << plain.err;
  write("em.add.xml",
        "<additional>\n<edgeData id=\"em\" type=\"emissions\" file=\"em.xml\"/>\n</additional>\n");
  expect_input_error(
      run({"run", "-n", test::kGridTlsNet, "-r", "r.rou.xml", "-a", "em.add.xml"}), "r.rou.xml:3",
      {"vType 'h4'", "emissionClass 'HBEFA4/PC_petrol_Euro-4'", "edgeData 'em' (em.add.xml:2)"});
}

class EmissionScenarioCliTest : public ::testing::Test {
 protected:
  // emissions_free in folder `tag`, to the end of its trips, with `extra` options; its laneData output.
  test::MeanDataEntries lanes(const std::string& tag, const std::vector<std::string>& extra) {
    const fs::path dir = tmp_.path() / tag;
    test::copy_scenario("emissions_free", dir);
    std::vector<std::string> args{"run", "emissions_free.sumocfg", "-a", "emissions.add.xml", "--end", "200"};
    args.insert(args.end(), extra.begin(), extra.end());
    const test::CliResult r = test::run_lpsim(dir, args);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return test::meandata_entries(test::read_file(dir / "lanes.xml"));
  }

  test::TempDir tmp_{"lpsim_emission_cli"};
};

TEST_F(EmissionScenarioCliTest, VolumetricFuelIsInMillilitres) {
  const test::MeanDataEntries mass = lanes("mass", {});
  const test::MeanDataEntries volume = lanes("volume", {"--emissions.volumetric-fuel"});
  ASSERT_EQ(mass.size(), volume.size());
  ASSERT_FALSE(mass.empty());
  for (const auto& [key, values] : mass) {
    const auto& other = volume.at(key);
    EXPECT_NEAR(other.at("fuel_abs"), values.at("fuel_abs") / 742, 1e-5) << std::get<2>(key);  // petrol
    EXPECT_EQ(other.at("CO2_abs"), values.at("CO2_abs"));
  }
}

TEST_F(EmissionScenarioCliTest, SnapshotRunWritesTheSameEmissions) {
  const fs::path dir = tmp_.path() / "snapshot";
  test::copy_scenario("emissions_redlight", dir);
  const std::vector<std::string> inputs{"-c", "emissions_redlight.sumocfg", "-a", "emissions.add.xml"};
  std::vector<std::string> run_xml{"run", "--end", "200"};
  run_xml.insert(run_xml.end(), inputs.begin(), inputs.end());
  ASSERT_EQ(test::run_lpsim(dir, run_xml).exit_code, 0);
  const std::string from_xml = test::read_file(dir / "edges_60.xml");
  std::vector<std::string> convert{"convert", "-o", "s.lpsim"};
  convert.insert(convert.end(), inputs.begin(), inputs.end());
  const test::CliResult c = test::run_lpsim(dir, convert);
  ASSERT_EQ(c.exit_code, 0) << c.err;
  fs::remove(dir / "edges_60.xml");
  const test::CliResult r = test::run_lpsim(dir, {"run", "s.lpsim", "--end", "200"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(from_xml.find("CO2_abs"), std::string::npos);
  EXPECT_EQ(test::read_file(dir / "edges_60.xml"), from_xml);
}

}  // namespace
}  // namespace lpsim

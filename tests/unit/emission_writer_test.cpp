// The emissions edgeData/laneData writer: exact text from known sums (SUMO 1.15's attribute order, line
// breaks and number formats: 6 decimals, "0" for zero, scientific below the precision), the derived
// values (normed, traveltime, perVeh), empty entries with and without excludeEmpty, the defaults of
// excludeEmpty="defaults" against SUMO's own output, and validity against SUMO's meandata schema.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "converters/emission_mean_data.hpp"
#include "converters/mean_data_writer.hpp"
#include "converters/output_file.hpp"
#include "sumo_schema.hpp"
#include "temp_dir.hpp"

namespace lpsim {
namespace {

namespace fs = std::filesystem;

// Edges: E1 (2 lanes of 100 m), :J_0 (internal), E2 (one lane of 300 m at 13.89 m/s), W (no car lanes).
Network emission_network() {
  Network net;
  net.edge_id = {"E1", ":J_0", "E2", "W"};
  net.edge_first_lane = {0, 2, 3, 4};
  net.edge_num_lanes = {2, 1, 1, 0};
  net.edge_is_internal = {0, 1, 0, 0};
  net.edge_length = {100, 8, 300, 50};
  net.edge_speed = {12.5f, 10, 13.89f, 5};
  net.lane_id = {"E1_0", "E1_1", ":J_0_0", "E2_0"};
  net.lane_edge = {0, 0, 1, 2};
  net.lane_length = {100, 100, 8, 300};
  net.lane_speed = {12.5f, 12.5f, 10, 13.89f};
  return net;
}

// E1_0: 30 s over 300 m; E1_1: 10 s over 100 m; the rest empty. Masses in ng.
LaneCounters known_sums() {
  LaneCounters c;
  c.resize(4, true);
  c.emission[kEmissionMicroseconds] = {30'000'000, 10'000'000, 0, 0};
  c.emission[kEmissionMicrometres] = {300'000'000, 100'000'000, 0, 0};
  c.emission[emission_mass_sum(kPollutantCO)] = {0, 0, 0, 0};
  c.emission[emission_mass_sum(kPollutantCO2)] = {90'000'000'000, 30'000'000'000, 0, 0};
  c.emission[emission_mass_sum(kPollutantHC)] = {500'000, 250'000, 0, 0};
  c.emission[emission_mass_sum(kPollutantPMx)] = {1, 0, 0, 0};
  c.emission[emission_mass_sum(kPollutantNOx)] = {12'400'000, 0, 0, 0};
  c.emission[emission_mass_sum(kPollutantFuel)] = {28'000'000'000, 0, 0, 0};
  return c;
}

class EmissionWriterTest : public ::testing::Test {
 protected:
  std::string write(const MeanDataSpec& spec) {
    const LaneCounters sums = known_sums();
    {
      MeanDataWriter writer(spec, net_, demand_);
      writer.write({0, 60, 1.0, &sums});
      writer.close();
    }
    return read(spec.file);
  }

  MeanDataSpec spec(const std::string& name, bool lane_level = false) const {
    MeanDataSpec s;
    s.id = "em";
    s.file = (tmp_.path() / name).string();
    s.lane_level = lane_level;
    s.type = MeanDataType::Emissions;
    return s;
  }

  static std::string read(const std::string& file) {
    std::ifstream in(file, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  }

  // The lines between the root's opening and closing tags.
  static std::vector<std::string> body(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text.substr(text.find("<meandata")));
    std::string line;
    std::getline(in, line);
    while (std::getline(in, line) && line != "</meandata>") lines.push_back(line);
    return lines;
  }

  void expect_schema_valid(const std::string& file) {
    const std::string schema = std::string(test::kSumoXsdDir) + "/meandata_file.xsd";
    if (std::system("xmllint --version > /dev/null 2>&1") != 0) GTEST_SKIP() << "xmllint not installed";
    if (!fs::exists(schema)) GTEST_SKIP() << schema << " not installed";
    const std::string log = (tmp_.path() / "xmllint.log").string();
    const std::string cmd = "xmllint --noout --schema " + test::usable_sumo_schema(schema, tmp_) + " " +
                            file + " > " + log + " 2>&1";
    EXPECT_EQ(std::system(cmd.c_str()), 0) << file << ":\n" << read(log);
  }

  test::TempDir tmp_{"lpsim_emission_writer"};
  Network net_ = emission_network();
  Demand demand_;
};

TEST_F(EmissionWriterTest, EdgeDataWritesSumosAttributesAndFormats) {
  const MeanDataSpec s = spec("edges.xml");
  const std::vector<std::string> expected = {
      "    <interval begin=\"0.00\" end=\"60.00\" id=\"em\">",
      // E1: 40 s and 400 m on a 100 m edge over 60 s: normed = abs * 0.6, perVeh = abs * min(1e5 / 40,
      // 100 / 400), traveltime 100 * 40 / 400.
      "        <edge id=\"E1\" sampledSeconds=\"40.00\" CO_abs=\"0\" CO2_abs=\"120000.000000\" "
      "HC_abs=\"0.750000\" "
      "PMx_abs=\"0.000001\" NOx_abs=\"12.400000\" fuel_abs=\"28000.000000\" electricity_abs=\"0\"",
      "            CO_normed=\"0\" CO2_normed=\"72000.000000\" HC_normed=\"0.450000\" "
      "PMx_normed=\"6.000000e-07\" "
      "NOx_normed=\"7.440000\" fuel_normed=\"16800.000000\" electricity_normed=\"0\"",
      "            traveltime=\"10.00\" CO_perVeh=\"0\" CO2_perVeh=\"30000.000000\" HC_perVeh=\"0.187500\" "
      "PMx_perVeh=\"2.500000e-07\" NOx_perVeh=\"3.100000\" fuel_perVeh=\"7000.000000\" "
      "electricity_perVeh=\"0\"/>",
      // Empty: written (excludeEmpty false), zeros, no traveltime or perVeh. Internal edges left out.
      "        <edge id=\"E2\" sampledSeconds=\"0.00\" CO_abs=\"0\" CO2_abs=\"0\" HC_abs=\"0\" PMx_abs=\"0\" "
      "NOx_abs=\"0\" fuel_abs=\"0\" electricity_abs=\"0\"",
      "            CO_normed=\"0\" CO2_normed=\"0\" HC_normed=\"0\" PMx_normed=\"0\" NOx_normed=\"0\" "
      "fuel_normed=\"0\" electricity_normed=\"0\"/>",
      "        <edge id=\"W\" sampledSeconds=\"0.00\" CO_abs=\"0\" CO2_abs=\"0\" HC_abs=\"0\" PMx_abs=\"0\" "
      "NOx_abs=\"0\" fuel_abs=\"0\" electricity_abs=\"0\"",
      "            CO_normed=\"0\" CO2_normed=\"0\" HC_normed=\"0\" PMx_normed=\"0\" NOx_normed=\"0\" "
      "fuel_normed=\"0\" electricity_normed=\"0\"/>",
      "    </interval>",
  };
  EXPECT_EQ(body(write(s)), expected);
  expect_schema_valid(s.file);
}

TEST_F(EmissionWriterTest, LaneDataNestsLanesAndExcludeEmptyLeavesThemOut) {
  MeanDataSpec s = spec("lanes.xml", true);
  s.exclude_empty = true;
  s.with_internal = true;
  const std::vector<std::string> lines = body(write(s));
  ASSERT_EQ(lines.size(), 10u);
  EXPECT_EQ(lines[1], "        <edge id=\"E1\">");
  EXPECT_EQ(lines[2],
            "            <lane id=\"E1_0\" sampledSeconds=\"30.00\" CO_abs=\"0\" CO2_abs=\"90000.000000\" "
            "HC_abs=\"0.500000\" PMx_abs=\"0.000001\" NOx_abs=\"12.400000\" fuel_abs=\"28000.000000\" "
            "electricity_abs=\"0\"");
  EXPECT_EQ(
      lines[4].rfind("            traveltime=\"10.00\" CO_perVeh=\"0\" CO2_perVeh=\"30000.000000\" ", 0), 0u)
      << lines[4];
  EXPECT_EQ(lines[5].rfind("            <lane id=\"E1_1\" sampledSeconds=\"10.00\" ", 0), 0u) << lines[5];
  EXPECT_EQ(lines[8], "        </edge>");  // nothing on :J_0, E2 or W
  expect_schema_valid(s.file);
}

// SUMO 1.15 on a 300 m edge at 13.89 m/s with excludeEmpty="defaults" (its default vehicle type, HBEFA3/
// PC_G_EU4, at the speed limit): traveltime="21.60" CO_perVeh="1797.506877" CO2_perVeh="131199.340689"
// fuel_perVeh="41846.302936".
TEST_F(EmissionWriterTest, ExcludeEmptyDefaultsWritesTheDefaultVehiclesValues) {
  MeanDataSpec s = spec("defaults.xml");
  s.empty_defaults = true;
  const std::string text = write(s);
  const size_t e2 = text.find("<edge id=\"E2\"");
  ASSERT_NE(e2, std::string::npos);
  const std::string entry = text.substr(e2, text.find("/>", e2) - e2);
  auto value = [&](const std::string& name) {
    std::smatch m;
    EXPECT_TRUE(std::regex_search(entry, m, std::regex(" " + name + "=\"([^\"]*)\""))) << name;
    return m.empty() ? -1.0 : std::stod(m[1]);
  };
  EXPECT_NE(entry.find(" sampledSeconds=\"0.00\" CO_abs=\"0\""), std::string::npos) << entry;
  EXPECT_NE(entry.find(" traveltime=\"21.60\""), std::string::npos) << entry;
  // LPSim keeps lane speeds as floats: 13.89 is 13.8900003 there.
  EXPECT_NEAR(value("CO_perVeh"), 1797.506877, 1797.506877 * 1e-7);
  EXPECT_NEAR(value("CO2_perVeh"), 131199.340689, 131199.340689 * 1e-7);
  EXPECT_NEAR(value("fuel_perVeh"), 41846.302936, 41846.302936 * 1e-7);
  expect_schema_valid(s.file);
}

TEST(SumoRealText, AsOutputDeviceRealString) {
  const test::TempDir tmp("lpsim_real");
  const std::string file = (tmp.path() / "r.txt").string();
  {
    OutputFile out(file);
    for (const double v : {0.0, 916.9487051, 0.000001, 0.0000005, 21.598272, 0.0071994, 1e5})
      out.real(v, v > 1 || v == 0.0071994 ? 2 : 6), out.put(' ');
    out.close();
  }
  std::ifstream in(file);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text, "0 916.95 0.000001 5.000000e-07 21.60 7.199400e-03 100000.00 ");
}

}  // namespace
}  // namespace lpsim

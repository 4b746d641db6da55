#include "converters/sumocfg_reader.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "core/error.hpp"
#include "temp_dir.hpp"

namespace lpsim {
namespace {

class SumocfgReaderTest : public ::testing::Test {
 protected:
  void SetUp() override { std::filesystem::create_directories(tmp_.path() / "sub"); }

  std::string write(const std::string& name, const std::string& text) const { return tmp_.write(name, text); }

  std::string in_dir(const std::string& rel) const { return (tmp_.path() / rel).lexically_normal().string(); }

  test::TempDir tmp_{"lpsim_cfg"};
};

TEST_F(SumocfgReaderTest, ReadsOptionsAndResolvesPathsAgainstTheCfgFolder) {
  std::string path = write("sub/run.sumocfg", R"(<?xml version="1.0" encoding="UTF-8"?>
<configuration xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance" xsi:noNamespaceSchemaLocation="http://sumo.dlr.de/xsd/sumoConfiguration.xsd">
    <input>
        <net-file value="net.net.xml.gz"/>
        <route-files value="a.rou.xml, b.rou.xml,../c.rou.xml"/>
        <additional-files value="x.add.xml y.add.xml"/>
    </input>
    <time>
        <begin value="1:00:00"/>
        <end value="0:2:00:30.5"/>
        <step-length value="0.5"/>
    </time>
    <processing>
        <time-to-teleport value="-1"/>
        <ignore-route-errors value="true"/>
        <threads value="4"/>
    </processing>
    <random_number><seed value="42"/></random_number>
    <output>
        <fcd-output value="out/fcd.xml"/>
        <device.fcd.period value="5"/>
        <tripinfo-output value="/abs/tripinfo.xml"/>
        <summary-output value="summary.xml"/>
        <edgedata-output value="edges.xml"/>
        <lanedata-output value="lanes.xml"/>
    </output>
    <report><log value="sumo_log.txt"/><no-step-log value="true"/></report>
    <gui_only><gui-settings-file value="settings.gui.xml"/></gui_only>
</configuration>
)");
  ConfigSpec c = read_sumocfg(path);
  EXPECT_EQ(c.config_file, path);
  EXPECT_EQ(c.net_file, in_dir("sub/net.net.xml.gz"));
  EXPECT_EQ(c.route_files, (std::vector<std::string>{in_dir("sub/a.rou.xml"), in_dir("sub/b.rou.xml"),
                                                     in_dir("c.rou.xml")}));
  EXPECT_EQ(c.additional_files, (std::vector<std::string>{in_dir("sub/x.add.xml"), in_dir("sub/y.add.xml")}));
  EXPECT_DOUBLE_EQ(c.begin, 3600);
  EXPECT_DOUBLE_EQ(c.end, 7230.5);
  EXPECT_DOUBLE_EQ(c.step_length, 0.5);
  EXPECT_DOUBLE_EQ(c.time_to_teleport, -1);
  EXPECT_TRUE(c.ignore_route_errors);
  EXPECT_EQ(c.threads, 4);
  EXPECT_EQ(c.seed, 42);
  EXPECT_EQ(c.outputs.fcd, in_dir("sub/out/fcd.xml"));
  EXPECT_DOUBLE_EQ(c.outputs.fcd_period, 5);
  EXPECT_EQ(c.outputs.tripinfo, "/abs/tripinfo.xml");
  EXPECT_EQ(c.outputs.summary, in_dir("sub/summary.xml"));
  EXPECT_EQ(c.outputs.edgedata, in_dir("sub/edges.xml"));
  EXPECT_EQ(c.outputs.lanedata, in_dir("sub/lanes.xml"));
  EXPECT_TRUE(c.output_file.empty());
}

TEST_F(SumocfgReaderTest, DefaultsWhenOptionsAreAbsentAndSumoConfigurationRoot) {
  std::string path =
      write("run.sumocfg",
            "<sumoConfiguration>\n  <input><net n=\"1\"/><net-file value=\"n.net.xml\"/></input>\n"
            "</sumoConfiguration>\n");
  ConfigSpec c = read_sumocfg(path);
  EXPECT_EQ(c.net_file, in_dir("n.net.xml"));
  EXPECT_TRUE(c.route_files.empty());
  ConfigSpec defaults;
  EXPECT_DOUBLE_EQ(c.begin, defaults.begin);
  EXPECT_DOUBLE_EQ(c.end, defaults.end);
  EXPECT_EQ(c.seed, defaults.seed);
  EXPECT_DOUBLE_EQ(c.time_to_teleport, defaults.time_to_teleport);
}

TEST_F(SumocfgReaderTest, SynonymsAsSumoAcceptsThem) {
  std::string path = write("syn.sumocfg",
                           "<configuration>\n<net value=\"a.net.xml\"/>\n<routes value=\"r.xml\"/>\n"
                           "<additional value=\"x.xml,y.xml\"/>\n</configuration>\n");
  ConfigSpec c = read_sumocfg(path);
  EXPECT_EQ(c.net_file, in_dir("a.net.xml"));
  EXPECT_EQ(c.route_files.size(), 1u);
  EXPECT_EQ(c.additional_files.size(), 2u);
}

TEST_F(SumocfgReaderTest, BadNumberNamesFileLineOptionAndValue) {
  std::string path =
      write("bad.sumocfg",
            "<configuration>\n  <time>\n    <begin value=\"0\"/>\n    <end value=\"soon\"/>\n  </time>\n"
            "</configuration>\n");
  try {
    read_sumocfg(path);
    FAIL() << "no error";
  } catch (const InputError& e) {
    std::string msg = e.what();
    EXPECT_NE(msg.find(path + ":4:"), std::string::npos) << msg;
    EXPECT_NE(msg.find("<end>"), std::string::npos) << msg;
    EXPECT_NE(msg.find("'soon'"), std::string::npos) << msg;
  }
}

TEST_F(SumocfgReaderTest, BadValuesOfOtherKinds) {
  auto message = [&](const std::string& option, const std::string& value) {
    std::string path =
        write("v.sumocfg", "<configuration>\n<" + option + " value=\"" + value + "\"/>\n</configuration>\n");
    try {
      read_sumocfg(path);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("seed", "1.5").find("'1.5'"), std::string::npos);
  EXPECT_NE(message("step-length", "0").find("from 0.001 to 86400 s"), std::string::npos);
  EXPECT_NE(message("ignore-route-errors", "maybe").find("'maybe'"), std::string::npos);
  EXPECT_NE(message("threads", "-2").find("'-2'"), std::string::npos);
  EXPECT_NE(message("device.fcd.period", "-5").find(":2:"), std::string::npos);
  EXPECT_NE(message("begin", "1:2").find("'1:2'"), std::string::npos);
}

TEST_F(SumocfgReaderTest, WrongRootMissingAndMalformedFiles) {
  EXPECT_THROW(read_sumocfg(write("net.sumocfg", "<net>\n</net>\n")), InputError);
  EXPECT_THROW(read_sumocfg((tmp_.path() / "missing.sumocfg").string()), InputError);
  EXPECT_THROW(read_sumocfg(write("cut.sumocfg", "<configuration>\n<input>\n<net-file value=\"a")),
               InputError);
}

}  // namespace
}  // namespace lpsim

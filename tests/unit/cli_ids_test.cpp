// Ids that would break the XML outputs or the one-line messages are refused at load, as SUMO refuses them:
// control characters (which XML carries only as character references such as &#9;, or as a raw DEL) in
// any id or id reference of a net, route or add-file, and control characters or invalid UTF-8 in the ids
// of the LPSim CSV tables (raw bytes). The message names file:line and shows the id with \xNN escapes.
#include <gtest/gtest.h>

#include <string>

#include "cli_scenario_fixture.hpp"

namespace lpsim {
namespace {

using test::CliScenarioTest;
using test::expect_input_error;

using CliIdsTest = CliScenarioTest;

const char* kRoute = "<route edges=\"A0A1 A1A2\"/>";

TEST_F(CliIdsTest, ControlCharacterReferencesInRouteFileIdsAreRefused) {
  const std::string route = kRoute;
  struct Case {
    std::string elements, element, attribute, shown, code;
  };
  const Case cases[] = {
      {"<vehicle id=\"a&#9;b\" depart=\"0\">" + route + "</vehicle>", "<vehicle id=\"a\\x09b\">", "'id'",
       "'a\\x09b'", "U+0009"},
      {"<vehicle id=\"v\" depart=\"0\" type=\"t&#10;\">" + route + "</vehicle>", "<vehicle id=\"v\">",
       "'type'", "'t\\x0A'", "U+000A"},
      {"<vType id=\"t&#13;x\"/>", "<vType id=\"t\\x0Dx\">", "'id'", "'t\\x0Dx'", "U+000D"},
      {"<route id=\"r&#9;\" edges=\"A0A1\"/>", "<route id=\"r\\x09\">", "'id'", "'r\\x09'", "U+0009"},
      {"<flow id=\"f&#10;\" begin=\"0\" number=\"1\">" + route + "</flow>", "<flow id=\"f\\x0A\">", "'id'",
       "'f\\x0A'", "U+000A"},
      {"<vehicle id=\"v\" depart=\"0\">\n<route edges=\"A0A1&#9;A1A2\"/></vehicle>", "<route>", "'edges'",
       "'A0A1\\x09A1A2'", "U+0009"},
      {"<vehicle id=\"a\x7f\" depart=\"0\">" + route + "</vehicle>", "<vehicle id=\"a\\x7F\">", "'id'",
       "'a\\x7F'", "U+007F"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.elements);
    write_routes("ids.rou.xml", c.elements);
    const auto r = info_with_routes("ids.rou.xml");
    const std::string line = c.element == "<route>" ? "4" : "3";
    expect_input_error(r, "ids.rou.xml:" + line,
                       {c.element, "attribute " + c.attribute, "control character " + c.code, c.shown});
  }
}

TEST_F(CliIdsTest, ControlCharacterInAnEdgeDataIdIsRefused) {
  write("data.add.xml",
        "<additional>\n<!-- test input -->\n<edgeData id=\"d&#9;\" file=\"out.xml\"/>\n</additional>\n");
  expect_input_error(run({"info", "-n", test::kGridTlsNet, "-a", "data.add.xml"}), "data.add.xml:3",
                     {"<edgeData id=\"d\\x09\">", "U+0009"});
}

TEST_F(CliIdsTest, ControlCharacterInANetIdIsRefused) {
  write_grid_net_with("edge.net.xml", "<edge id=\"A0A1\"", "<edge id=\"A0&#10;A1\"");
  expect_input_error(run({"info", "-n", "edge.net.xml"}), "edge.net.xml:1228",
                     {"<edge id=\"A0\\x0AA1\">", "attribute 'id'", "U+000A"});
  write_grid_net_with("lane.net.xml", "<lane id=\"A0A1_0\"", "<lane id=\"A0A1&#9;0\"");
  expect_input_error(run({"info", "-n", "lane.net.xml"}), "lane.net.xml:1229", {"<lane id=\"A0A1\\x090\">"});
}

// The CSV reader reads raw bytes: NUL, other control characters and invalid UTF-8 reach it as they are.
TEST_F(CliIdsTest, CsvIdsWithControlCharactersOrInvalidUtf8AreRefused) {
  const std::string edges = "uniqueid,u,v,length\ne1,n1,n2,100\ne2,n2,n1,100\n";
  struct Case {
    std::string node, shown, problem;
  };
  const Case cases[] = {
      {std::string("n\0x", 3), "n\\x00x", "control character U+0000"},
      {"n\x01x", "n\\x01x", "control character U+0001"},
      {"n\xffx", "n\\xFFx", "not valid UTF-8 (byte \\xFF at offset 1)"},
      {"n\xc3", "n\\xC3", "not valid UTF-8 (byte \\xC3 at offset 1)"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.shown);
    write("nodes.csv", "osmid,x,y\nn1,0,0\n" + c.node + ",1,1\nn2,100,0\n");
    write("edges.csv", edges);
    expect_input_error(run({"info", "--lpsim-nodes", "nodes.csv", "--lpsim-edges", "edges.csv"}),
                       "nodes.csv:3", {"column 'osmid'", "'" + c.shown + "'", c.problem});
  }
  write("nodes.csv", "osmid,x,y\nn1,0,0\nn2,100,0\n");
  write("edges.csv", "uniqueid,u,v,length\ne\x1f,n1,n2,100\n");
  expect_input_error(run({"info", "--lpsim-nodes", "nodes.csv", "--lpsim-edges", "edges.csv"}), "edges.csv:2",
                     {"column 'uniqueid'", "'e\\x1F'", "U+001F"});
  // Valid UTF-8 beyond ASCII is an id like any other.
  write("nodes.csv", "osmid,x,y\nn1,0,0\n\xc3\xbc,100,0\n");
  write("edges.csv", "uniqueid,u,v,length\n\xc3\xa9,n1,\xc3\xbc,100\n");
  EXPECT_EQ(run({"info", "--lpsim-nodes", "nodes.csv", "--lpsim-edges", "edges.csv"}).exit_code, 0);
}

}  // namespace
}  // namespace lpsim

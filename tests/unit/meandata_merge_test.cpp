// merge_meandata: LPSim's edgeData/laneData output with the corridor's entries replaced by SUMO's, interval
// by interval; a corridor edge SUMO left out (nothing passed) is left out; an interval SUMO lacks is an
// error.
#include "converters/meandata_merge.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "core/error.hpp"
#include "temp_dir.hpp"

namespace lpsim {
namespace {

std::string read_all(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

const char* kLpsimEdges = R"(<?xml version="1.0" encoding="UTF-8"?>
<meandata>
    <interval begin="0.00" end="100.00" id="e">
        <edge id="a" sampledSeconds="1.00"/>
        <edge id="b" sampledSeconds="2.00"/>
        <edge id="c&amp;d" sampledSeconds="3.00"/>
    </interval>
    <interval begin="100.00" end="200.00" id="e">
        <edge id="a" sampledSeconds="4.00"/>
        <edge id="b" sampledSeconds="5.00"/>
    </interval>
</meandata>
)";

TEST(MeanDataMerge, CorridorEdgesComeFromSumoIntervalByInterval) {
  test::TempDir dir("merge");
  const std::string lpsim = dir.write("ed.xml", kLpsimEdges);
  const std::string sumo = dir.write("sumo.ed.xml", R"(<meandata>
    <interval begin="0.00" end="100.00" id="e">
        <edge id="b" sampledSeconds="20.50" speed="3.10"/>
        <edge id="c&amp;d" sampledSeconds="30.25"/>
        <edge id="a" sampledSeconds="99.00"/>
    </interval>
    <interval begin="100.00" end="200.00" id="e">
    </interval>
</meandata>
)");
  EXPECT_TRUE(merge_meandata(lpsim, sumo, {"b", "c&d"}).empty());
  EXPECT_EQ(read_all(lpsim), R"(<?xml version="1.0" encoding="UTF-8"?>
<meandata>
    <interval begin="0.00" end="100.00" id="e">
        <edge id="a" sampledSeconds="1.00"/>
        <edge id="b" sampledSeconds="20.50" speed="3.10"/>
        <edge id="c&amp;d" sampledSeconds="30.25"/>
    </interval>
    <interval begin="100.00" end="200.00" id="e">
        <edge id="a" sampledSeconds="4.00"/>
    </interval>
</meandata>
)");
}

TEST(MeanDataMerge, LaneDataEntriesAreReplacedWhole) {
  test::TempDir dir("merge");
  const std::string lpsim = dir.write("ld.xml", R"(<meandata>
    <interval begin="0.00" end="10.00" id="l">
        <edge id="a">
            <lane id="a_0" sampledSeconds="1.00"/>
        </edge>
        <edge id="b">
            <lane id="b_0" sampledSeconds="2.00"/>
            <lane id="b_1" sampledSeconds="3.00"/>
        </edge>
    </interval>
</meandata>
)");
  const std::string sumo = dir.write("sumo.ld.xml", R"(<meandata>
    <interval begin="0.00" end="10.00" id="l">
        <edge id="b">
            <lane id="b_1" sampledSeconds="7.00"/>
        </edge>
    </interval>
</meandata>
)");
  merge_meandata(lpsim, sumo, {"b"});
  EXPECT_EQ(read_all(lpsim), R"(<meandata>
    <interval begin="0.00" end="10.00" id="l">
        <edge id="a">
            <lane id="a_0" sampledSeconds="1.00"/>
        </edge>
        <edge id="b">
            <lane id="b_1" sampledSeconds="7.00"/>
        </edge>
    </interval>
</meandata>
)");
}

TEST(MeanDataMerge, AnIntervalSumoLacksIsAnErrorNamingTheLine) {
  test::TempDir dir("merge");
  const std::string lpsim = dir.write("ed.xml", kLpsimEdges);
  const std::string sumo = dir.write("sumo.ed.xml", R"(<meandata>
    <interval begin="0.00" end="100.00" id="e"/>
</meandata>
)");
  try {
    merge_meandata(lpsim, sumo, {"b"});
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("ed.xml:8"), std::string::npos) << e.what();
  }
  EXPECT_EQ(read_all(lpsim), kLpsimEdges);  // left as it was
}

// SUMO's last step may run past the end when its step is longer than LPSim's: the merge says which interval
// ends at different times on the two sides (the co-simulation warns), and merges it all the same.
TEST(MeanDataMerge, IntervalsEndingAtDifferentTimesAreReported) {
  test::TempDir dir("merge_span");
  const std::string lpsim = dir.write("ed.xml", kLpsimEdges);
  const std::string sumo = dir.write("sumo.ed.xml", R"(<meandata>
    <interval begin="0.00" end="100.00" id="e">
        <edge id="b" sampledSeconds="20.50"/>
    </interval>
    <interval begin="100.00" end="208.00" id="e">
        <edge id="b" sampledSeconds="50.00"/>
    </interval>
</meandata>
)");
  const std::vector<MeanDataSpanDiff> diffs = merge_meandata(lpsim, sumo, {"b"});
  ASSERT_EQ(diffs.size(), 1u);
  EXPECT_DOUBLE_EQ(diffs[0].begin, 100.0);
  EXPECT_DOUBLE_EQ(diffs[0].lpsim_end, 200.0);
  EXPECT_DOUBLE_EQ(diffs[0].sumo_end, 208.0);
  EXPECT_NE(read_all(lpsim).find("<edge id=\"b\" sampledSeconds=\"50.00\"/>"), std::string::npos);
}

}  // namespace
}  // namespace lpsim

// The run's end and the edgeData interval boundaries as SUMO 1.15 has them (measured on grid_tls): with
// --end 600 SUMO reports "Simulation ended at time: 600.00", its last interval ends at 600.00, and an
// interval [b, b + period) holds the vehicles that depart at b .. b + period - 1 s.
#include <gtest/gtest.h>

#include <regex>
#include <string>
#include <vector>

#include "lpsim_cli.hpp"
#include "temp_dir.hpp"

namespace lpsim {
namespace {

const std::string kGridCfg = std::string(LPSIM_SCENARIOS_DIR) + "/grid_tls/grid_tls.sumocfg";

struct Interval {
  std::string begin, end;
  int departed = 0;
};

// The intervals of an edgeData file with the vehicles departed on all its edges.
std::vector<Interval> intervals_of(const std::string& xml) {
  std::vector<Interval> out;
  const std::regex interval_tag(R"re(<interval begin="([0-9.]+)" end="([0-9.]+)")re");
  const std::regex departed(R"re(departed="([0-9]+)")re");
  size_t at = 0;
  std::smatch m;
  while (true) {
    const size_t next = xml.find("<interval ", at);
    if (next == std::string::npos) break;
    const size_t close = xml.find("</interval>", next);
    const std::string body = xml.substr(next, close - next);
    if (!std::regex_search(body, m, interval_tag)) break;
    Interval iv{m[1].str(), m[2].str(), 0};
    for (auto it = std::sregex_iterator(body.begin(), body.end(), departed); it != std::sregex_iterator();
         ++it)
      iv.departed += std::stoi((*it)[1].str());
    out.push_back(iv);
    at = close;
  }
  return out;
}

// grid_tls departs one vehicle per second from 0 and inserts each at once: every 100 s interval holds 100.
TEST(EndTimeTest, IntervalsAndTheReportEndWhereSumosDo) {
  const test::TempDir tmp("lpsim_end_time");
  tmp.write("p.add.xml",
            "<additional>\n    <edgeData id=\"p\" file=\"periodic.xml\" period=\"100\"/>\n</additional>\n");
  const auto r = test::run_lpsim(tmp.path(), {"run", "-c", kGridCfg, "-e", "600", "-a", "p.add.xml",
                                              "--edgedata-output", "whole.xml", "--no-warnings"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(
      r.out.find("Simulation ended at time: 600.00\nReason: The final simulation step has been reached.\n"),
      std::string::npos)
      << r.out;
  const auto periodic = intervals_of(test::read_file(tmp.path() / "periodic.xml"));
  ASSERT_EQ(periodic.size(), 6u);
  for (size_t k = 0; k < periodic.size(); ++k) {
    EXPECT_EQ(periodic[k].begin, std::to_string(100 * k) + ".00");
    EXPECT_EQ(periodic[k].end, std::to_string(100 * (k + 1)) + ".00");
    EXPECT_EQ(periodic[k].departed, 100) << "interval " << periodic[k].begin;
  }
  const auto whole = intervals_of(test::read_file(tmp.path() / "whole.xml"));
  ASSERT_EQ(whole.size(), 1u);
  EXPECT_EQ(whole[0].end, "600.00");
  EXPECT_EQ(whole[0].departed, 600);
}

// With an end time SUMO runs on to it after the last vehicle has left, and says so.
TEST(EndTimeTest, AnEndTimeIsTheReasonEvenAfterEveryVehicleLeft) {
  const test::TempDir tmp("lpsim_end_time");
  const auto r = test::run_lpsim(tmp.path(), {"run", "-c", kGridCfg, "-e", "3600", "--no-warnings"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find(" Arrived: 1000\n"), std::string::npos) << r.out;
  EXPECT_NE(
      r.out.find("Simulation ended at time: 3600.00\nReason: The final simulation step has been reached.\n"),
      std::string::npos)
      << r.out;
}

}  // namespace
}  // namespace lpsim

// `lpsim run` interrupted: a real SIGINT, SIGTERM or SIGHUP sent to the running binary ends the run at the
// end of a step with one line on stderr, exit status 128 + the signal, the report on stdout, and every output
// complete: well-formed XML, a whole gzip stream, the open edgeData/laneData interval written up to the stop.
// A SIGKILL cannot be handled: there the edgeData intervals that had closed must already be in the file.
#include <gtest/gtest.h>
#include <zlib.h>

#include <csignal>
#include <regex>
#include <string>
#include <vector>

#include "converters/xml_stream.hpp"
#include "lpsim_cli.hpp"
#include "spawned_lpsim.hpp"
#include "temp_dir.hpp"

namespace lpsim {
namespace {

const std::string kGridCfg = std::string(LPSIM_SCENARIOS_DIR) + "/grid_tls/grid_tls.sumocfg";

// The simulation time of the last progress line ("lpsim: t=12.00 running ...") on stderr, or -1.
double last_progress_time(const std::string& err) {
  static const std::regex line(R"(lpsim: t=([0-9.]+) running )");
  double t = -1;
  for (auto it = std::sregex_iterator(err.begin(), err.end(), line); it != std::sregex_iterator(); ++it)
    t = std::stod((*it)[1].str());
  return t;
}

// Reads the whole document; the parser's error if it is not well-formed and complete, else "". With
// `element` and `attr`, collects that attribute of every such element into `values`.
std::string xml_problem(const std::string& path, const std::string& element = "", const char* attr = "",
                        std::vector<double>* values = nullptr) {
  try {
    XmlStream xs(path);
    for (auto ev = xs.next(); ev != XmlStream::Event::Eof; ev = xs.next())
      if (values && ev == XmlStream::Event::Start && xs.name() == element)
        values->push_back(xs.required_number(attr));
    return "";
  } catch (const InputError& e) {
    return e.what();
  }
}

// zlib's verdict on a .gz file read to its end: "" for a complete stream (trailer and CRC included).
std::string gzip_problem(const std::string& path) {
  gzFile gz = gzopen(path.c_str(), "rb");
  if (gz == nullptr) return "cannot open";
  char buf[1 << 14];
  while (gzread(gz, buf, sizeof buf) > 0) {
  }
  int code = Z_OK;
  std::string problem = gzeof(gz) ? "" : "not read to its end";
  const char* message = gzerror(gz, &code);
  if (code != Z_OK) problem = message;
  gzclose(gz);
  return problem;
}

class CliInterruptTest : public ::testing::TestWithParam<int> {
 protected:
  // An add-file with edgeData and laneData intervals of `period` s, written to edge.xml and lane.xml.
  void write_mean_data(int period) const {
    const std::string p = std::to_string(period);
    tmp_.write("data.add.xml", "<additional>\n    <edgeData id=\"e\" file=\"edge.xml\" period=\"" + p +
                                   "\"/>\n    <laneData id=\"l\" file=\"lane.xml\" period=\"" + p +
                                   "\"/>\n</additional>\n");
  }
  std::string at(const std::string& name) const { return (tmp_.path() / name).string(); }

  // grid_tls with an end far beyond its demand (the run would take minutes), a progress line every 20 ms of
  // wall time (the test's sign that stepping has begun) and every output.
  std::vector<std::string> long_run_args() const {
    return {"run",           "-c",
            kGridCfg,        "-a",
            "data.add.xml",  "--end",
            "1000000",       "--progress-interval",
            "0.02",          "--fcd-output",
            "fcd.xml.gz",    "--tripinfo-output",
            "tripinfo.xml",  "--summary-output",
            "summary.xml",   "--statistic-output",
            "statistic.xml", "--no-warnings"};
  }

  test::TempDir tmp_{"lpsim_interrupt"};
};

TEST_P(CliInterruptTest, SignalEndsTheRunWithEveryOutputComplete) {
  const int signal = GetParam();
  const std::string name = signal == SIGINT ? "SIGINT" : signal == SIGTERM ? "SIGTERM" : "SIGHUP";
  write_mean_data(100);
  test::SpawnedLpsim lpsim(tmp_.path(), long_run_args());
  ASSERT_TRUE(lpsim.started());
  // Past the first edgeData interval, so that a closed one and an open one are both in play.
  ASSERT_TRUE(lpsim.wait_until([&] { return last_progress_time(lpsim.err()) >= 150; }, 8)) << lpsim.err();
  lpsim.send(signal);
  const int status = lpsim.wait_exit(8);
  ASSERT_NE(status, -1) << "still running 8 s after " << name;
  ASSERT_TRUE(WIFEXITED(status)) << "ended by signal " << WTERMSIG(status);
  EXPECT_EQ(WEXITSTATUS(status), 128 + signal);

  // One line says so, naming the signal and the time the run stopped at.
  const std::string err = lpsim.err();
  EXPECT_EQ(err.find('\r'), std::string::npos);
  const std::regex said("(^|\n)lpsim: interrupted by " + name +
                        " at time ([0-9]+\\.[0-9]{2}); outputs closed\n");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(err, m, said)) << err;
  const double stop = std::stod(m[2].str());
  // As SUMO, the stop is reported at the end of the last step; the outputs' last sample is that step's
  // (grid_tls steps 1 s).
  const double last_step = stop - 1;
  EXPECT_GE(stop, 150);
  EXPECT_LT(stop, 1000000);
  // Every other line is a progress line.
  for (size_t from = 0, nl; (nl = err.find('\n', from)) != std::string::npos; from = nl + 1) {
    const std::string line = err.substr(from, nl - from);
    EXPECT_TRUE(line.rfind("lpsim: t=", 0) == 0 || line.rfind("lpsim: interrupted by ", 0) == 0 ||
                line.rfind("lpsim: warning: ", 0) == 0)
        << line;
  }
  const std::string out = lpsim.out();
  EXPECT_NE(out.find("Simulation ended at time: " + m[2].str() + "\nReason: Interrupted by " + name + ".\n"),
            std::string::npos)
      << out;

  // Every output is complete and runs to the stop.
  std::vector<double> steps, timesteps, trips, begins, ends, lane_ends, stats;
  EXPECT_EQ(xml_problem(at("summary.xml"), "step", "time", &steps), "");
  ASSERT_FALSE(steps.empty());
  EXPECT_DOUBLE_EQ(steps.back(), last_step);
  EXPECT_EQ(gzip_problem(at("fcd.xml.gz")), "");
  EXPECT_EQ(xml_problem(at("fcd.xml.gz"), "timestep", "time", &timesteps), "");
  ASSERT_FALSE(timesteps.empty());
  EXPECT_DOUBLE_EQ(timesteps.back(), last_step);
  EXPECT_EQ(xml_problem(at("tripinfo.xml"), "tripinfo", "arrival", &trips), "");
  EXPECT_FALSE(trips.empty());
  EXPECT_EQ(xml_problem(at("statistic.xml"), "vehicles", "inserted", &stats), "");
  EXPECT_EQ(stats.size(), 1u);
  // edgeData: the closed intervals, then the open one written up to the stop (as SUMO does on Ctrl-C).
  EXPECT_EQ(xml_problem(at("edge.xml"), "interval", "begin", &begins), "");
  EXPECT_EQ(xml_problem(at("edge.xml"), "interval", "end", &ends), "");
  ASSERT_GE(ends.size(), 2u);
  ASSERT_EQ(begins.size(), ends.size());
  for (size_t k = 0; k + 1 < ends.size(); ++k) {
    EXPECT_DOUBLE_EQ(begins[k], 100.0 * static_cast<double>(k));
    EXPECT_DOUBLE_EQ(ends[k], begins[k] + 100);
  }
  EXPECT_DOUBLE_EQ(begins.back(), 100.0 * static_cast<double>(ends.size() - 1));
  EXPECT_DOUBLE_EQ(ends.back(), stop);
  EXPECT_EQ(xml_problem(at("lane.xml"), "interval", "end", &lane_ends), "");
  EXPECT_EQ(lane_ends, ends);
}

INSTANTIATE_TEST_SUITE_P(Signals, CliInterruptTest, ::testing::Values(SIGINT, SIGTERM, SIGHUP),
                         [](const ::testing::TestParamInfo<int>& info) {
                           return std::string(info.param == SIGINT    ? "SIGINT"
                                              : info.param == SIGTERM ? "SIGTERM"
                                                                      : "SIGHUP");
                         });

using CliKillTest = CliInterruptTest;

// SIGKILL: nothing can be closed, but every edgeData interval that had closed is in the file, whole. The
// intervals are small (a few on grid_tls fill less than an output's buffer), so that this holds only
// because each interval is flushed as it closes.
TEST_F(CliKillTest, KilledRunKeepsEveryClosedInterval) {
  write_mean_data(100);
  test::SpawnedLpsim lpsim(tmp_.path(), long_run_args());
  ASSERT_TRUE(lpsim.started());
  double seen = -1;
  ASSERT_TRUE(lpsim.wait_until([&] { return (seen = last_progress_time(lpsim.err())) >= 250; }, 8))
      << lpsim.err();
  lpsim.send(SIGKILL);
  const int status = lpsim.wait_exit(8);
  ASSERT_TRUE(WIFSIGNALED(status));

  // Cut after the last whole interval and closed by hand, the file is well-formed and holds at least the
  // intervals that had closed by the last progress line seen.
  const std::string text = test::read_file(at("edge.xml"));
  const size_t last = text.rfind("</interval>\n");
  ASSERT_NE(last, std::string::npos) << "no whole interval in edge.xml (" << text.size() << " bytes)";
  tmp_.write("edge_closed.xml", text.substr(0, last + 12) + "</meandata>\n");
  std::vector<double> ends;
  EXPECT_EQ(xml_problem(at("edge_closed.xml"), "interval", "end", &ends), "");
  EXPECT_GE(ends.size(), static_cast<size_t>(seen / 100));
  for (size_t k = 0; k < ends.size(); ++k) EXPECT_DOUBLE_EQ(ends[k], 100.0 * static_cast<double>(k + 1));
}

// A signal while the scenario loads, before any output exists, may end the process at once; either way
// no output is left half-written: each one is either absent or complete.
TEST_F(CliKillTest, SignalDuringStartLeavesNoHalfWrittenOutput) {
  write_mean_data(100);
  test::SpawnedLpsim lpsim(tmp_.path(), long_run_args());
  ASSERT_TRUE(lpsim.started());
  lpsim.send(SIGINT);
  const int status = lpsim.wait_exit(8);
  ASSERT_NE(status, -1);
  if (WIFSIGNALED(status)) {
    EXPECT_EQ(WTERMSIG(status), SIGINT);
    for (const char* f :
         {"summary.xml", "fcd.xml.gz", "tripinfo.xml", "statistic.xml", "edge.xml", "lane.xml"})
      EXPECT_FALSE(std::filesystem::exists(at(f))) << f;
  } else {
    EXPECT_EQ(WEXITSTATUS(status), 130) << lpsim.err();
    for (const char* f :
         {"summary.xml", "fcd.xml.gz", "tripinfo.xml", "statistic.xml", "edge.xml", "lane.xml"})
      EXPECT_EQ(xml_problem(at(f)), "") << f;
  }
}

}  // namespace
}  // namespace lpsim

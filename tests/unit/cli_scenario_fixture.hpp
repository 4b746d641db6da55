// A fixture for CLI tests that run the real `lpsim` on small files written to a temp dir beside the
// grid_tls network, and the checks they share: an input error is exit status 2 and exactly one stderr line
// "lpsim: error: <file>:<line>: ..." naming the values given; a warning is one exact stderr line.
#pragma once

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "lpsim_cli.hpp"
#include "temp_dir.hpp"

namespace lpsim::test {

inline const std::string kGridTlsNet = std::string(LPSIM_SCENARIOS_DIR) + "/grid_tls/grid_tls.net.xml";

class CliScenarioTest : public ::testing::Test {
 protected:
  void write(const std::string& name, const std::string& text) const { tmp_.write(name, text); }
  // A route file whose elements start on line 3 (line 2 is a comment), so that a reported line 3 is the
  // element's own.
  void write_routes(const std::string& name, const std::string& elements) const {
    write(name, "<routes>\n<!-- test input -->\n" + elements + "\n</routes>\n");
  }
  // The grid_tls network with the first occurrence of `from` replaced by `to`.
  void write_grid_net_with(const std::string& name, const std::string& from, const std::string& to) const {
    std::string net = read_file(kGridTlsNet);
    const size_t at = net.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    net.replace(at, from.size(), to);
    write(name, net);
  }
  CliResult run(const std::vector<std::string>& args) const { return run_lpsim(tmp_.path(), args); }
  CliResult info_with_routes(const std::string& routes) const {
    return run({"info", "-n", kGridTlsNet, "-r", routes});
  }

  TempDir tmp_{"lpsim_cli_scenario"};
};

// Exit status 2; stderr exactly one line starting "lpsim: error: <where>: " and containing each of `parts`.
inline void expect_input_error(const CliResult& r, const std::string& where,
                               const std::vector<std::string>& parts) {
  EXPECT_EQ(r.exit_code, 2) << r.err;
  const auto lines = lines_of(r.err);
  ASSERT_EQ(lines.size(), 1u) << r.err;
  const std::string prefix = "lpsim: error: " + where + ": ";
  EXPECT_EQ(lines[0].rfind(prefix, 0), 0u) << "expected prefix '" << prefix << "' in: " << lines[0];
  for (const auto& p : parts)
    EXPECT_NE(lines[0].find(p), std::string::npos) << "'" << p << "' missing in: " << lines[0];
}

// True when stderr holds exactly the line `line`.
inline bool has_line(const CliResult& r, const std::string& line) {
  for (const auto& l : lines_of(r.err))
    if (l == line) return true;
  return false;
}

}  // namespace lpsim::test

// Running the real `lpsim` binary from a test: one place for the command line, the redirection of its
// output and the decoding of its exit status, shared by the tests that check what a user sees.
#pragma once

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace lpsim::test {

/// A file's bytes ("" if it cannot be read).
inline std::string read_file(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

/// Whether SUMO's program `name` (sumo, netconvert, ...) can be run: on the PATH or in $SUMO_HOME/bin. Tests
/// that need it skip without it.
inline bool have_sumo_tool(const std::string& name) {
  if (std::system(("command -v " + name + " > /dev/null 2>&1").c_str()) == 0) return true;
  const char* home = std::getenv("SUMO_HOME");
  return home != nullptr && std::filesystem::exists(std::filesystem::path(home) / "bin" / name);
}

/// `s` quoted for the shell, whatever it contains.
inline std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

struct CliResult {
  int exit_code = -1;  // 128 + the signal if it was killed by one
  std::string out, err;
};

/// Runs `program` (its words, e.g. {"python3", "tool.py"}) with `args` (each passed as one word) in `dir`,
/// which receives stdout.txt and stderr.txt.
inline CliResult run_program(const std::filesystem::path& dir, const std::vector<std::string>& program,
                             const std::vector<std::string>& args) {
  // SUMO validates files that name a schema against those under SUMO_HOME and fails without it: where it is
  // unset, Debian's, as lpsim's own SUMO start does (sumo_bridge/sumo_start.cpp), so that a plain ctest
  // runs SUMO as tools/test.sh does.
  if (std::getenv("SUMO_HOME") == nullptr && std::filesystem::exists("/usr/share/sumo/data/xsd"))
    ::setenv("SUMO_HOME", "/usr/share/sumo", 0);
  // Appended piecewise: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string temporaries.
  std::string cmd = "cd ";
  cmd += shell_quote(dir.string());
  cmd += " &&";
  for (const auto& word : program) {
    cmd += ' ';
    cmd += shell_quote(word);
  }
  for (const auto& a : args) {
    cmd += ' ';
    cmd += shell_quote(a);
  }
  cmd += " > stdout.txt 2> stderr.txt";
  const int status = std::system(cmd.c_str());
  CliResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
  r.out = read_file(dir / "stdout.txt");
  r.err = read_file(dir / "stderr.txt");
  return r;
}

/// Runs LPSIM_BINARY with `args` in `dir` (see run_program).
inline CliResult run_lpsim(const std::filesystem::path& dir, const std::vector<std::string>& args) {
  return run_program(dir, {LPSIM_BINARY}, args);
}

/// The lines of `text` (a stream's output), without their line ends.
inline std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  size_t start = 0;
  while (start < text.size()) {
    size_t nl = text.find('\n', start);
    if (nl == std::string::npos) nl = text.size();
    lines.push_back(text.substr(start, nl - start));
    start = nl + 1;
  }
  return lines;
}

}  // namespace lpsim::test

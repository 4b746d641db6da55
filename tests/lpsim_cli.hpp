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

/// Runs LPSIM_BINARY with `args` (each passed as one word) in `dir`, which receives stdout.txt and
/// stderr.txt.
inline CliResult run_lpsim(const std::filesystem::path& dir, const std::vector<std::string>& args) {
  // Appended piecewise: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string temporaries.
  std::string cmd = "cd ";
  cmd += shell_quote(dir.string());
  cmd += " && ";
  cmd += shell_quote(LPSIM_BINARY);
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

}  // namespace lpsim::test

#pragma once
// What the mpirun tests share: whether mpirun is there, a bundled scenario's path, and the shell that runs an
// lpsim job in a folder and signals its ranks once it has stepped a while.
#include <filesystem>
#include <string>

#include "lpsim_cli.hpp"

namespace lpsim::test {

inline bool have_mpirun() { return std::filesystem::exists(LPSIM_MPIEXEC); }

/// Bundled scenario `name`'s .sumocfg.
inline std::string scenario(const std::string& name) {
  // Appended, not a chain of operator+: GCC 12 at -O1 warns falsely (-Warray-bounds) on that chain.
  std::string cfg = LPSIM_SOURCE_DIR;
  cfg.append("/scenarios/").append(name).append("/").append(name).append(".sumocfg");
  return cfg;
}

/// Routes for grid_tls beside its hour of demand: a flow that never ends, so that vehicles are on the road
/// whenever a signal comes.
inline constexpr const char* kEndlessFlow =
    "<routes>\n    <flow id=\"long\" begin=\"0\" end=\"1000000\" period=\"20\" from=\"A0A1\" "
    "to=\"A1A2\"/>\n</routes>\n";

/// A shell command that runs `job` (an mpirun command line) in `dir` with its stdout and stderr in out.txt
/// and err.txt, runs `signal` (a command that may use $job, mpirun's pid, and $(mine), the pids of this job's
/// lpsim processes: found by their working directory, as other tests run lpsim at the same time) once rank 0
/// has written the first few hundred steps of summary.xml, and writes the job's exit status to status.txt.
inline std::string signalled_job(const std::filesystem::path& dir, const std::string& job,
                                 const std::string& signal) {
  return "cd " + shell_quote(dir.string()) +
         " && mine() { for p in $(pgrep -x lpsim); do [ \"$(readlink /proc/$p/cwd)\" = \"$PWD\" ] "
         "&& echo $p; done; }; (" +
         job +
         " > out.txt 2> err.txt & job=$!; for i in $(seq 4000); do "
         "[ $(stat -c %s summary.xml 2>/dev/null || echo 0) -gt 40000 ] && break; sleep 0.005; done; " +
         signal + "; wait $job; echo $? > status.txt)";
}

}  // namespace lpsim::test

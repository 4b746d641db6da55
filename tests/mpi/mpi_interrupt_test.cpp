// `mpirun -n 2 lpsim run ... --parts 2` interrupted (label mpi), as a user (Ctrl-C: SIGINT to mpirun, which
// passes SIGTERM to every rank), a batch system (SIGTERM to every rank at once) or an operator (SIGTERM to
// one rank other than rank 0) would: every rank stops at the same step, rank 0 closes every output
// well-formed (a whole gzip stream, edgeData up to the stop), its tripinfo is a prefix of the uninterrupted
// run's, and the ranks exit 128 + the signal. Before, ranks other than rank 0 died at once and rank 0's
// exchange failed: empty tripinfo, edgeData and statistics, a cut summary and FCD, exit 1.
#include <gtest/gtest.h>

#include <filesystem>
#include <regex>
#include <string>
#include <vector>

#include "converters/xml_stream.hpp"
#include "lpsim_cli.hpp"
#include "mpi/mpi_job.hpp"
#include "temp_dir.hpp"

namespace lpsim {
namespace {

namespace fs = std::filesystem;

using test::have_mpirun;

const std::string kGrid = std::string(LPSIM_SOURCE_DIR) + "/scenarios/grid_tls/grid_tls.sumocfg";

// The parser's error if the document is not well-formed and complete (a .gz read to its end), else "".
std::string xml_problem(const fs::path& path) {
  try {
    XmlStream xs(path.string());
    while (xs.next() != XmlStream::Event::Eof) {
    }
    return "";
  } catch (const InputError& e) {
    return e.what();
  }
}

// The <tripinfo .../> lines of a tripinfo output, in order.
std::vector<std::string> trip_lines(const std::string& text) {
  static const std::regex line("<tripinfo [^\n]*");
  std::vector<std::string> out;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), line); it != std::sregex_iterator(); ++it)
    out.push_back(it->str());
  return out;
}

// `sigkill_wait`: mpirun's odls_base_sigkill_timeout, how long it lets ranks it passed a signal on to end
// before it kills them (default 1 s). It also waits about that long, twice, whenever a rank ends non-zero.
std::string mpirun_command(const std::string& args, int sigkill_wait = 1) {
  return test::shell_quote(LPSIM_MPIEXEC) +
         " -n 2 --allow-run-as-root --oversubscribe --mca odls_base_sigkill_timeout " +
         std::to_string(sigkill_wait) + " " + test::shell_quote(LPSIM_BINARY) + " run " +
         test::shell_quote(kGrid) + " --parts 2 " + args;
}

// Besides grid_tls's hour of demand, a flow that never ends: trips arrive whenever the signal comes.
const char* const kOutputs =
    " -a ../long.rou.xml --tripinfo-output trip.xml --fcd-output fcd.xml.gz --summary-output summary.xml"
    " --statistic-output stat.xml --edgedata-output edge.xml --no-step-log";

class MpiInterruptTest : public ::testing::TestWithParam<const char*> {};

TEST_P(MpiInterruptTest, EveryRankStopsAtOneStepAndRankZeroClosesTheOutputs) {
  if (!have_mpirun()) GTEST_SKIP() << "mpirun not installed";
  const std::string how = GetParam();
  test::TempDir tmp("lpsim_mpi_interrupt");
  tmp.write("long.rou.xml", test::kEndlessFlow);
  const fs::path cut_dir = tmp.path() / "cut", whole_dir = tmp.path() / "whole";
  fs::create_directory(cut_dir);
  fs::create_directory(whole_dir);
  const std::string signal = how == std::string("mpirun")  ? "kill -INT $job"
                             : how == std::string("ranks") ? "for p in $(mine); do kill -TERM $p; done"
                                                           : "for p in $(mine); do grep -qz "
                                                             "'^OMPI_COMM_WORLD_RANK=1$' /proc/$p/environ && "
                                                             "kill -TERM $p; done";
  const std::string cmd = test::signalled_job(
      cut_dir, mpirun_command(std::string("--end 1000000") + kOutputs, how == std::string("mpirun") ? 3 : 1),
      signal);
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  const int status = std::stoi(test::read_file(cut_dir / "status.txt"));
  const std::string err = test::read_file(cut_dir / "err.txt");
  // mpirun, itself signalled, ends with its own status (OpenMPI: 1) once the ranks have ended.
  if (how == std::string("mpirun"))
    EXPECT_NE(status, 0) << err;
  else
    EXPECT_EQ(status, 128 + SIGTERM) << err;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(
      err, m, std::regex("lpsim: interrupted by SIGTERM at time ([0-9.]+); outputs closed")))
      << err;
  const double stop = std::stod(m[1]);
  EXPECT_NE(test::read_file(cut_dir / "out.txt").find("Reason: Interrupted by SIGTERM."), std::string::npos);
  EXPECT_EQ(err.find("MPI_ABORT"), std::string::npos) << err;
  for (const char* f : {"trip.xml", "fcd.xml.gz", "summary.xml", "stat.xml", "edge.xml"})
    EXPECT_EQ(xml_problem(cut_dir / f), "") << f;
  EXPECT_NE(test::read_file(cut_dir / "edge.xml").find("end=\"" + m[1].str()), std::string::npos);

  // The same job run uninterrupted to a little past the stop.
  const std::string end = std::to_string(static_cast<int>(stop) + 200);
  ASSERT_EQ(std::system(("cd " + test::shell_quote(whole_dir.string()) + " && " +
                         mpirun_command("--end " + end + kOutputs) + " > out.txt 2> err.txt")
                            .c_str()),
            0)
      << test::read_file(whole_dir / "err.txt");
  const std::vector<std::string> cut = trip_lines(test::read_file(cut_dir / "trip.xml"));
  const std::vector<std::string> whole = trip_lines(test::read_file(whole_dir / "trip.xml"));
  ASSERT_FALSE(cut.empty());
  ASSERT_LT(cut.size(), whole.size());
  for (size_t k = 0; k < cut.size(); ++k) ASSERT_EQ(cut[k], whole[k]) << k;
}

INSTANTIATE_TEST_SUITE_P(Signals, MpiInterruptTest, ::testing::Values("mpirun", "ranks", "rank1"),
                         [](const ::testing::TestParamInfo<const char*>& info) {
                           return std::string(info.param);
                         });

}  // namespace
}  // namespace lpsim

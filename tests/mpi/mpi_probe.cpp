// K ranks of the MPI transport under mpirun, for tests/mpi/mpi_transport_test.cpp:
//   mpi_probe ring ROUNDS      each round every rank sends its neighbours a buffer that says who sent it in
//                              which round, and checks what it receives; prints "ok" on rank 0
//   mpi_probe stall            rank 1 stops answering after the build check: rank 0 must report it
//   mpi_probe die              rank 1 exits after the build check: the job must end with an error
//   mpi_probe mismatch         rank 1 claims another build: every rank must refuse to go on
// A TransportError is printed as "lpsim: error: ..." and ends the whole job (MPI_Abort) with status 3.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>

#include "transport/mpi/mpi_transport.hpp"

namespace {

lpsim::Bytes message(int from, int to, int round) {
  const std::string s = std::to_string(from) + ">" + std::to_string(to) + "@" + std::to_string(round);
  return lpsim::Bytes(s.begin(), s.end());
}

}  // namespace

int main(int argc, char** argv) {
  lpsim::MpiSession session(&argc, &argv);
  const std::string mode = argc > 1 ? argv[1] : "ring";
  try {
    // Short patience only where a rank is meant to fall silent: under a loaded ctest the ranks of a job
    // may start seconds apart, and the build check must then still hear the other rank's answer.
    lpsim::MpiTransport transport(mode == "stall" || mode == "die" ? 2.0 : 30.0);
    const int rank = transport.rank(), size = transport.size();
    transport.check_same_build(mode == "mismatch" && rank == 1 ? "other-build" : "this-build");
    if (mode == "die" && rank == 1) std::_Exit(7);
    if (mode == "stall" && rank == 1) std::this_thread::sleep_for(std::chrono::seconds(30));
    const int rounds = mode == "ring" && argc > 2 ? std::atoi(argv[2]) : 3;
    const int next = (rank + 1) % size, prev = (rank + size - 1) % size;
    for (int r = 0; r < rounds; ++r) {
      const auto got = transport.exchange({next, prev}, {message(rank, next, r), message(rank, prev, r)},
                                          {prev, next}, "ring");
      if (got[0] != message(prev, rank, r) || got[1] != message(next, rank, r)) {
        std::fprintf(stderr, "lpsim: error: rank %d got wrong data in round %d\n", rank, r);
        lpsim::MpiSession::abort_job(4);
      }
    }
    const auto all = transport.allgather(message(rank, -1, rounds), "gather");
    for (int r = 0; r < size; ++r)
      if (all[static_cast<size_t>(r)] != message(r, -1, rounds)) lpsim::MpiSession::abort_job(5);
    if (rank == 0) std::printf("ok %d ranks, %d rounds\n", size, rounds);
  } catch (const lpsim::TransportError& e) {
    std::fprintf(stderr, "lpsim: error: %s\n", e.what());
    std::fflush(stderr);
    lpsim::MpiSession::abort_job(3);
  }
  return 0;
}

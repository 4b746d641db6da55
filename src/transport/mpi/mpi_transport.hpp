#pragma once
// The MPI transport: one rank per process under `mpirun -n K` (Debian's OpenMPI, not CUDA-aware: buffers
// are host memory). Rounds are non-blocking sends and probed receives of any size, polled against a timeout,
// so that a stalled peer becomes an error naming it instead of a hang; a peer that dies is reported by
// mpirun, which ends the job.
#include <string>

#include "transport/transport.hpp"

namespace lpsim {

/// MPI_Init / MPI_Finalize around a run (one per process).
class MpiSession {
 public:
  MpiSession(int* argc, char*** argv);
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
  /// Ends every rank of the job with `code` (after an error on this one, so the others do not wait).
  [[noreturn]] static void abort_job(int code);
  /// Every rank calls it at the same point, each saying whether it failed and with which exit status: the
  /// lowest rank that failed and its status, the same on every rank ({world_size(), 0} when none did).
  /// Waits without spinning a core on a rank that is still working.
  struct Failure {
    int rank, code;
  };
  static Failure first_failure(bool failed, int code);
  /// This process was started by OpenMPI's mpirun (its environment says so): MPI is to be initialised.
  static bool launched_by_mpirun();
  /// Ranks of the job; 1 where MPI is not initialised.
  static int world_size();
  /// This rank's number in the job (0 where MPI is not initialised).
  static int world_rank();
  /// This rank's number among the job's ranks on the same machine (0 where MPI is not initialised).
  static int local_rank();
};

class MpiTransport : public Transport {
 public:
  /// A round waits at most timeout_s seconds for each peer.
  explicit MpiTransport(double timeout_s);
  int rank() const override { return rank_; }
  int size() const override { return size_; }
  std::vector<Bytes> exchange(const std::vector<int>& to, const std::vector<Bytes>& send,
                              const std::vector<int>& from, const std::string& what) override;

 private:
  int rank_ = 0, size_ = 1;
  double timeout_s_;
  uint64_t round_ = 0;
};

}  // namespace lpsim

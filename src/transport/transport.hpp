#pragma once
// How the parts of a partitioned run talk: bulk-synchronous rounds of byte buffers between ranks (the LAMMPS
// style exchanges of the partitioned step), in-process (K ranks as threads, in_process_transport.hpp) or over
// MPI (one process per rank, mpi/mpi_transport.hpp). Every rank makes the same rounds in the same order; a
// peer that does not answer within the timeout is an error naming it and the round, never a hang.
#include <stdint.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace lpsim {

using Bytes = std::vector<uint8_t>;

/// A peer that died, stalled past the timeout, or runs another build.
class TransportError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// "2", "0.3": a timeout in seconds as errors name it.
std::string seconds_text(double s);

class Transport {
 public:
  virtual ~Transport() = default;
  virtual int rank() const = 0;
  virtual int size() const = 0;

  /// One round: sends send[i] to rank to[i] and returns the buffer of each rank from[j], in that order.
  /// `what` names the round in errors.
  virtual std::vector<Bytes> exchange(const std::vector<int>& to, const std::vector<Bytes>& send,
                                      const std::vector<int>& from, const std::string& what) = 0;

  /// Every rank's buffer, in rank order, on every rank (one round with all others).
  std::vector<Bytes> allgather(const Bytes& mine, const std::string& what);

  /// Refuses to go on unless every rank runs the same build: `build_id` (the commit and what the build was
  /// configured with) is compared across ranks in the first round.
  void check_same_build(const std::string& build_id);
};

}  // namespace lpsim

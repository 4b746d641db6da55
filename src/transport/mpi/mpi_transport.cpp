#include "transport/mpi/mpi_transport.hpp"

#include <mpi.h>

#include <chrono>
#include <cstdlib>
#include <thread>

namespace lpsim {

namespace {

// A peer's buffer usually arrives within microseconds of the round starting (the step's passes are balanced):
// poll, yielding the core, for this long before sleeping between polls.
constexpr auto kPollBeforeSleep = std::chrono::microseconds(500);

// Waits between two polls of a round started at `start`. The longer a round waits, the longer the sleeps: a
// peer that is slow this step is met within 20 us, one still building its tables or stopped (SIGSTOP, a
// debugger) costs a few polls a second instead of a core spinning in MPI's progress engine.
void pause(std::chrono::steady_clock::time_point start) {
  using std::chrono::microseconds, std::chrono::milliseconds;
  const auto waited = std::chrono::steady_clock::now() - start;
  if (waited < kPollBeforeSleep)
    std::this_thread::yield();
  else if (waited < milliseconds(50))
    std::this_thread::sleep_for(microseconds(20));
  else if (waited < milliseconds(1000))
    std::this_thread::sleep_for(milliseconds(1));
  else
    std::this_thread::sleep_for(milliseconds(20));
}

// Rounds go in lock-step, so a tag that wraps after 32,768 rounds (the least MPI_TAG_UB MPI allows) never
// meets a message of another round still in flight.
int round_tag(uint64_t round) { return static_cast<int>(round % 32768); }

}  // namespace

MpiSession::MpiSession(int* argc, char*** argv) { MPI_Init(argc, argv); }

MpiSession::~MpiSession() { MPI_Finalize(); }

void MpiSession::abort_job(int code) {
  MPI_Abort(MPI_COMM_WORLD, code);
  std::exit(code);  // not reached: MPI_Abort ends the process
}

namespace {

void wait_for(MPI_Request* request) {
  const auto start = std::chrono::steady_clock::now();
  for (int done = 0; MPI_Test(request, &done, MPI_STATUS_IGNORE), !done;) pause(start);
}

}  // namespace

MpiSession::Failure MpiSession::first_failure(bool failed, int code) {
  const int size = world_size();
  int mine = failed ? world_rank() : size, first = size;
  MPI_Request request;
  MPI_Iallreduce(&mine, &first, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD, &request);
  wait_for(&request);
  if (first == size) return Failure{size, 0};
  MPI_Ibcast(&code, 1, MPI_INT, first, MPI_COMM_WORLD, &request);
  wait_for(&request);
  return Failure{first, code};
}

bool MpiSession::launched_by_mpirun() { return std::getenv("OMPI_COMM_WORLD_SIZE") != nullptr; }

int MpiSession::world_size() {
  int initialised = 0;
  MPI_Initialized(&initialised);
  if (!initialised) return 1;
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  return size;
}

int MpiSession::world_rank() {
  if (world_size() == 1) return 0;
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  return rank;
}

int MpiSession::local_rank() {
  if (world_size() == 1) return 0;
  MPI_Comm local;
  MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &local);
  int rank = 0;
  MPI_Comm_rank(local, &rank);
  MPI_Comm_free(&local);
  return rank;
}

MpiTransport::MpiTransport(double timeout_s) : timeout_s_(timeout_s) {
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

std::vector<Bytes> MpiTransport::exchange(const std::vector<int>& to, const std::vector<Bytes>& send,
                                          const std::vector<int>& from, const std::string& what) {
  const int tag = round_tag(round_);
  const uint64_t round = round_++;
  std::vector<MPI_Request> sends(to.size());
  for (size_t i = 0; i < to.size(); ++i)
    MPI_Isend(send[i].data(), static_cast<int>(send[i].size()), MPI_BYTE, to[i], tag, MPI_COMM_WORLD,
              &sends[i]);
  const auto start = std::chrono::steady_clock::now();
  const auto deadline = start + std::chrono::duration<double>(timeout_s_);
  auto timed_out = [&](const std::string& doing, int peer) {
    return TransportError("rank " + std::to_string(rank_) + ": " + doing + " rank " + std::to_string(peer) +
                          " in round '" + what + "' (#" + std::to_string(round) + ") took more than " +
                          seconds_text(timeout_s_) + " s: has it stopped?");
  };
  std::vector<Bytes> got(from.size());
  for (size_t j = 0; j < from.size(); ++j) {
    int flag = 0;
    MPI_Message message;
    MPI_Status status;
    while (true) {
      MPI_Improbe(from[j], tag, MPI_COMM_WORLD, &flag, &message, &status);
      if (flag) break;
      if (std::chrono::steady_clock::now() > deadline) throw timed_out("receiving from", from[j]);
      pause(start);
    }
    int count = 0;
    MPI_Get_count(&status, MPI_BYTE, &count);
    got[j].resize(static_cast<size_t>(count));
    MPI_Mrecv(got[j].data(), count, MPI_BYTE, &message, MPI_STATUS_IGNORE);
  }
  for (size_t i = 0; i < sends.size(); ++i) {
    int done = 0;
    while (true) {
      MPI_Test(&sends[i], &done, MPI_STATUS_IGNORE);
      if (done) break;
      if (std::chrono::steady_clock::now() > deadline) throw timed_out("sending to", to[i]);
      pause(start);
    }
  }
  return got;
}

}  // namespace lpsim

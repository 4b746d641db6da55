#include "app/error_report.hpp"

#include <cstdio>
#include <new>

#include "core/error.hpp"
#include "transport/mpi/mpi_transport.hpp"
#include "transport/transport.hpp"

namespace lpsim {

int exit_status_of(std::exception_ptr error) {
  try {
    std::rethrow_exception(error);
  } catch (const InputError&) {
    return kExitBadInput;
  } catch (...) {
    return 1;
  }
}

int report_error(std::exception_ptr error) {
  try {
    std::rethrow_exception(error);
  } catch (const InputError& e) {
    std::fprintf(stderr, "lpsim: error: %s\n", e.what());
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "lpsim: error: out of memory\n");
  } catch (const TransportError& e) {
    // A part that stopped or died is a fault of the job, not of LPSim.
    std::fprintf(stderr, "lpsim: error: %s\n", e.what());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lpsim: internal error: %s\n", e.what());
  } catch (...) {
    std::fprintf(stderr, "lpsim: internal error: unknown exception\n");
  }
  return exit_status_of(error);
}

void agree_on_load(std::exception_ptr error) {
  const MpiSession::Failure first =
      MpiSession::first_failure(error != nullptr, error ? exit_status_of(error) : 0);
  if (first.rank == MpiSession::world_size()) return;
  throw JobEnded(first.code, first.rank == MpiSession::world_rank() ? error : nullptr);
}

}  // namespace lpsim

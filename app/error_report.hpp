#pragma once
// How a command's error ends the process: one line on stderr and an exit status (2: bad input or usage,
// 1: a fault or an internal failure). Under mpirun an error while loading ends every rank together.
#include <exception>

namespace lpsim {

/// The exit status `error` ends a command with.
int exit_status_of(std::exception_ptr error);

/// Prints `error` as one line ("lpsim: error: ..." for bad input and faults, "lpsim: internal error: ..."
/// for anything else) and returns exit_status_of(error).
int report_error(std::exception_ptr error);

/// The ranks of an MPI job agreed to end before any part ran: an error while loading, on one rank or on all.
/// Every rank ends with `code` and none waits for another; `cause` is the error of the lowest rank that saw
/// one (printed there), null on the others (which print nothing).
struct JobEnded : std::exception {
  JobEnded(int code_, std::exception_ptr cause_) : code(code_), cause(std::move(cause_)) {}
  const char* what() const noexcept override { return "the job ended while loading"; }
  int code;
  std::exception_ptr cause;
};

/// Under mpirun, every rank calls this once it has loaded, with the error it met (null: none): returns when
/// no rank failed, else throws JobEnded on every rank.
void agree_on_load(std::exception_ptr error);

/// Runs `load()`; in a job of more than one rank, every rank then learns whether any failed (agree_on_load),
/// so that an error is printed once and every rank ends together.
template <class Load>
void load_on_every_rank(int ranks, Load&& load) {
  if (ranks <= 1) {
    load();
    return;
  }
  std::exception_ptr error;
  try {
    load();
  } catch (...) {
    error = std::current_exception();
  }
  agree_on_load(error);
}

}  // namespace lpsim

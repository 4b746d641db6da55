#pragma once
// The loop that steps a command's run to its end, shared by `lpsim run` (a Run) and `lpsim cosim` (a
// Cosimulation), and the place a remote-control server's loop would take too.
#include "app/progress_log.hpp"
#include "engine/simulation.hpp"

namespace lpsim {

/// Steps `stepped` (done(), step()) until it is done or `signalled()` returns a signal, with a progress line
/// about `sim` after each step.
template <class Stepped, class Signalled>
void drive_to_end(Stepped& stepped, const Simulation& sim, ProgressLog& progress, Signalled&& signalled) {
  while (!stepped.done() && signalled() == 0) {
    stepped.step();
    progress.after_step(sim);
  }
}

}  // namespace lpsim

#pragma once
// The convergence plot of `lpsim assign --plot`: each iteration's relative gap on a logarithmic axis, as a
// PNG drawn with cairo.
#include <string>
#include <vector>

namespace lpsim {

/// Plots gaps[i] (iteration i; values <= 0 are left out) to `path`. A file that cannot be written is an
/// InputError naming it.
void write_gap_plot(const std::string& path, const std::vector<double>& gaps);

}  // namespace lpsim

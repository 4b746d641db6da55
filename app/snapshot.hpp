#pragma once
// `lpsim convert`: a binary snapshot of a loaded scenario (network + demand + output definitions) that later
// runs load far faster than XML. Format: magic "LPSIMSNP", format version, payload size, CRC-32 of the
// payload, then the payload (length-prefixed arrays, little-endian as the host). A snapshot of another
// version, a truncated one or one whose checksum does not match is refused with an InputError.
#include <string>

#include "app/scenario.hpp"

namespace lpsim {

inline constexpr uint32_t kSnapshotVersion = 10;  // 2: car-following model; 3: actuated loops; 4: vClasses;
                                                  // 5: keepClear links; 6: scheduled stops; 7: emissions;
                                                  // 8: desiredMaxSpeed; 9: speed restrictions by vClass;
                                                  // 10: the rerouting device

void write_snapshot(const Scenario& scenario, const std::string& path);
Scenario read_snapshot(const std::string& path);
/// True when the file starts with the snapshot magic (so the CLI can take either a snapshot or XML).
bool is_snapshot(const std::string& path);

}  // namespace lpsim

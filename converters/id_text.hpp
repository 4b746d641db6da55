#pragma once
// Ids must survive into XML outputs and one-line error messages: SUMO refuses ids with control characters
// or invalid UTF-8, and so does LPSim, at load, naming file:line. XML can carry them only as character
// references (&#9; &#10; &#13;: a literal tab or newline in an attribute becomes a space), the LPSim CSV
// reader reads raw bytes.
#include <string>
#include <string_view>

namespace lpsim {

/// What makes `id` unusable as an id: a control character (U+0000 to U+001F, U+007F) or a byte sequence
/// that is not UTF-8; "" when there is none.
std::string id_problem(std::string_view id);

/// `text` with control characters and bytes outside valid UTF-8 written as \xNN, so that a message quoting
/// it stays one printable line.
std::string printable(std::string_view text);

}  // namespace lpsim

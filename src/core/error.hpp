#pragma once
// Errors that carry their context. Every problem with user input becomes an InputError whose message is
// one line naming file:line, the offending value or id and the element using it; the CLI prints it and
// exits with status 2. Internal invariant violations are plain std::logic_error.
#include <stdexcept>
#include <string>
#include <string_view>

namespace lpsim {

/// `text` made fit for one line of a terminal: control bytes (a NUL, a newline, escape sequences) written as
/// \xNN, and a text longer than 2,000 bytes (an id of megabytes) cut in its middle, saying how much.
inline std::string printable_message(std::string_view text) {
  constexpr size_t kLongest = 2000, kHead = 1500, kTail = 400;
  std::string cut;
  if (text.size() > kLongest) {
    cut.append(text.substr(0, kHead));
    cut += " [... " + std::to_string(text.size() - kHead - kTail) + " bytes left out ...] ";
    cut.append(text.substr(text.size() - kTail));
    text = cut;
  }
  std::string out;
  out.reserve(text.size());
  constexpr char kHex[] = "0123456789abcdef";
  for (const char ch : text) {
    const auto c = static_cast<unsigned char>(ch);
    if (c < 0x20 || c == 0x7f) {
      out += "\\x";
      out += kHex[c >> 4];
      out += kHex[c & 15];
    } else {
      out += ch;
    }
  }
  return out;
}

/// Where in an input file something was read from. line 0 means "the file as a whole".
struct SourceLoc {
  std::string file;
  int line = 0;

  std::string str() const { return line > 0 ? file + ":" + std::to_string(line) : file; }
};

class InputError : public std::runtime_error {
 public:
  // The message is made printable here: ids from input files may hold any byte, a NUL too, which what()
  // would otherwise cut the message at.
  InputError(const SourceLoc& where, const std::string& what)
      : std::runtime_error(printable_message(where.str() + ": " + what)), where_(where) {}
  explicit InputError(const std::string& what) : std::runtime_error(printable_message(what)) {}
  const SourceLoc& where() const { return where_; }

 private:
  SourceLoc where_;
};

/// Exit status for bad input, as promised in the README.
inline constexpr int kExitBadInput = 2;

}  // namespace lpsim

#pragma once
// Errors that carry their context. Every problem with user input becomes an InputError whose message is
// one line naming file:line, the offending value or id and the element using it; the CLI prints it and
// exits with status 2. Internal invariant violations are plain std::logic_error.
#include <stdexcept>
#include <string>

namespace lpsim {

/// Where in an input file something was read from. line 0 means "the file as a whole".
struct SourceLoc {
  std::string file;
  int line = 0;

  std::string str() const { return line > 0 ? file + ":" + std::to_string(line) : file; }
};

class InputError : public std::runtime_error {
 public:
  InputError(const SourceLoc& where, const std::string& what)
      : std::runtime_error(where.str() + ": " + what), where_(where) {}
  explicit InputError(const std::string& what) : std::runtime_error(what) {}
  const SourceLoc& where() const { return where_; }

 private:
  SourceLoc where_;
};

/// Exit status for bad input, as promised in the README.
inline constexpr int kExitBadInput = 2;

}  // namespace lpsim

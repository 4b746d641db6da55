#include "converters/csv_table.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include "converters/id_text.hpp"

namespace lpsim {

namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

// Splits `text` into records. Each field's unescaped text is appended to a store and its start offset
// recorded.
class Splitter {
 public:
  Splitter(std::string_view text, const std::string& file) : text_(text), file_(file) {
    if (text_.substr(0, 3) == "\xEF\xBB\xBF") pos_ = 3;  // UTF-8 byte order mark
  }

  bool done() const { return pos_ >= text_.size(); }
  int line() const { return line_; }

  // Reads one record (appending to `store` and `starts`); returns false for a blank line.
  bool next_record(std::string& store, std::vector<uint32_t>& starts, size_t& count) {
    count = 0;
    if (text_[pos_] == '\n' || (text_[pos_] == '\r' && pos_ + 1 < text_.size() && text_[pos_ + 1] == '\n')) {
      pos_ += text_[pos_] == '\r' ? 2 : 1;
      ++line_;
      return false;
    }
    for (;;) {
      if (store.size() > std::numeric_limits<uint32_t>::max())
        throw InputError(SourceLoc{file_, line_}, "CSV file too large (over 4 GiB of field text)");
      starts.push_back(static_cast<uint32_t>(store.size()));
      ++count;
      if (pos_ < text_.size() && text_[pos_] == '"') {
        read_quoted(store);
      } else {
        read_plain(store);
      }
      if (pos_ >= text_.size()) return true;
      const char c = text_[pos_];
      if (c == ',') {
        ++pos_;
        continue;
      }
      // end of record: \n or \r\n
      if (c == '\r' && (pos_ + 1 >= text_.size() || text_[pos_ + 1] != '\n')) lone_carriage_return();
      pos_ += c == '\r' ? 2 : 1;
      ++line_;
      return true;
    }
  }

 private:
  // A lone CR is how old Mac editors end lines: read as one long line, the file would blame a wrong field.
  [[noreturn]] void lone_carriage_return() const {
    throw InputError(
        SourceLoc{file_, line_},
        "carriage return without a line feed: the file has CR-only line ends (convert them to LF "
        "or CRLF)");
  }

  void read_plain(std::string& store) {
    const size_t begin = pos_;
    while (pos_ < text_.size()) {
      const char c = text_[pos_];
      if (c == ',' || c == '\n') break;
      if (c == '\r') {
        if (pos_ + 1 < text_.size() && text_[pos_ + 1] == '\n') break;
        lone_carriage_return();
      }
      if (c == '"')
        throw InputError(SourceLoc{file_, line_}, "quote inside an unquoted CSV field '" +
                                                      printable(text_.substr(begin, pos_ - begin + 1)) + "'");
      ++pos_;
    }
    store.append(text_.substr(begin, pos_ - begin));
  }

  void read_quoted(std::string& store) {
    const int start_line = line_;
    ++pos_;  // opening quote
    for (;;) {
      if (pos_ >= text_.size())
        throw InputError(SourceLoc{file_, start_line}, "unterminated quoted CSV field");
      const char c = text_[pos_++];
      if (c == '"') {
        if (pos_ < text_.size() && text_[pos_] == '"') {
          store.push_back('"');
          ++pos_;
          continue;
        }
        break;
      }
      if (c == '\n') ++line_;
      store.push_back(c);
    }
    if (pos_ >= text_.size()) return;
    const char c = text_[pos_];
    const bool crlf = c == '\r' && pos_ + 1 < text_.size() && text_[pos_ + 1] == '\n';
    if (c != ',' && c != '\n' && !crlf)
      throw InputError(SourceLoc{file_, line_},
                       std::string("unexpected character '") + c + "' after a closing quote in a CSV field");
  }

  std::string_view text_;
  const std::string& file_;
  size_t pos_ = 0;
  int line_ = 1;
};

std::string quoted_header(const std::vector<std::string>& header) {
  std::string s;
  for (const auto& h : header) s += (s.empty() ? "" : ",") + h;
  return s;
}

}  // namespace

CsvTable CsvTable::read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(SourceLoc{path, 0}, "cannot open CSV file");
  std::ostringstream buf;
  buf << in.rdbuf();
  if (in.bad()) throw InputError(SourceLoc{path, 0}, "cannot read CSV file");
  return parse(buf.str(), path);
}

CsvTable CsvTable::parse(std::string_view text, const std::string& file) {
  CsvTable t;
  t.file_ = file;
  Splitter split(text, file);
  std::string header_text;
  std::vector<uint32_t> header_starts;
  size_t count = 0;
  int header_line = 0;
  while (!split.done()) {
    header_line = split.line();
    if (split.next_record(header_text, header_starts, count)) break;
  }
  if (count == 0) throw InputError(SourceLoc{file, 0}, "empty CSV file: no header line");
  t.header_line_ = header_line;
  header_starts.push_back(static_cast<uint32_t>(header_text.size()));
  for (size_t i = 0; i < count; ++i) {
    std::string name(trim(
        std::string_view(header_text).substr(header_starts[i], header_starts[i + 1] - header_starts[i])));
    for (const auto& prev : t.header_)
      if (!name.empty() && prev == name)
        throw InputError(SourceLoc{file, header_line}, "duplicate CSV column '" + name + "'");
    t.header_.push_back(std::move(name));
  }

  t.text_.reserve(text.size());
  t.field_begin_.reserve(text.size() / 4);
  while (!split.done()) {
    const int line = split.line();
    if (!split.next_record(t.text_, t.field_begin_, count)) continue;
    if (count != t.header_.size()) {
      throw InputError(SourceLoc{file, line}, "CSV record has " + std::to_string(count) +
                                                  " fields, the header (" + quoted_header(t.header_) +
                                                  ") has " + std::to_string(t.header_.size()));
    }
    t.row_line_.push_back(line);
  }
  t.field_begin_.push_back(static_cast<uint32_t>(t.text_.size()));
  return t;
}

std::optional<size_t> CsvTable::find_column(std::string_view name) const {
  for (size_t i = 0; i < header_.size(); ++i)
    if (header_[i] == name) return i;
  return std::nullopt;
}

size_t CsvTable::column(std::string_view name) const {
  if (auto c = find_column(name)) return *c;
  throw InputError(SourceLoc{file_, header_line_},
                   "missing CSV column '" + std::string(name) + "' (header: " + quoted_header(header_) + ")");
}

std::string_view CsvTable::trimmed(size_t row, size_t col) const { return trim(field(row, col)); }

void CsvTable::fail(size_t row, size_t col, const std::string& what) const {
  throw InputError(loc(row), "column '" + printable(header_[col]) + "' value '" + printable(field(row, col)) +
                                 "': " + what);
}

std::string_view CsvTable::id(size_t row, size_t col) const {
  const std::string_view text = trimmed(row, col);
  if (const std::string problem = id_problem(text); !problem.empty()) fail(row, col, "the id " + problem);
  return text;
}

std::optional<double> CsvTable::optional_number(size_t row, size_t col) const {
  std::string_view s = trimmed(row, col);
  if (s.empty()) return std::nullopt;
  if (s.front() == '+') s.remove_prefix(1);
  double v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size()) fail(row, col, "not a number");
  if (!std::isfinite(v)) fail(row, col, "not a finite number");
  return v;
}

double CsvTable::number(size_t row, size_t col) const {
  if (auto v = optional_number(row, col)) return *v;
  fail(row, col, "missing number");
}

int64_t CsvTable::integer(size_t row, size_t col) const {
  const double v = number(row, col);
  if (v != std::floor(v) || std::fabs(v) > 9.0e15) fail(row, col, "not a whole number");
  return static_cast<int64_t>(v);
}

}  // namespace lpsim

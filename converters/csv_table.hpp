#pragma once
// A small strict CSV reader for the LPSim input tables. The first record is the header; columns are looked up
// by name. Fields may be quoted ("a,b", "say ""hi""", embedded newlines). Every data record must have as many
// fields as the header. Blank lines are skipped. Problems raise InputError naming file:line, the column and
// the offending value.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.hpp"

namespace lpsim {

class CsvTable {
 public:
  /// Reads and parses a whole file. Missing or unreadable file -> InputError naming the path.
  static CsvTable read_file(const std::string& path);
  /// Parses text already in memory; `file` names it in error messages.
  static CsvTable parse(std::string_view text, const std::string& file);

  const std::string& file() const { return file_; }
  size_t num_rows() const { return row_line_.size(); }
  size_t num_columns() const { return header_.size(); }
  const std::vector<std::string>& header() const { return header_; }

  /// Index of the column named `name` (surrounding spaces of header names are ignored), if present.
  std::optional<size_t> find_column(std::string_view name) const;
  /// As find_column, but a missing column is an InputError naming the file's header line.
  size_t column(std::string_view name) const;

  /// Raw text of a field (quotes removed, "" unescaped).
  std::string_view field(size_t row, size_t col) const {
    const size_t i = row * header_.size() + col;
    return std::string_view(text_).substr(field_begin_[i], field_begin_[i + 1] - field_begin_[i]);
  }
  /// The field with leading and trailing blanks removed.
  std::string_view trimmed(size_t row, size_t col) const;
  /// Where a data record starts (1-based line; the header is line 1 unless blank lines precede it).
  SourceLoc loc(size_t row) const { return SourceLoc{file_, row_line_[row]}; }

  /// The trimmed field as an id: control characters or invalid UTF-8 (converters/id_text.hpp) are an
  /// InputError naming the record's line, the column and the value.
  std::string_view id(size_t row, size_t col) const;
  /// A finite number; empty, non-numeric, NaN or infinite fields are InputErrors.
  double number(size_t row, size_t col) const;
  /// As number(), but an empty field gives nullopt.
  std::optional<double> optional_number(size_t row, size_t col) const;
  /// A whole number (written as "12" or "12.0"); anything else is an InputError.
  int64_t integer(size_t row, size_t col) const;

  /// Throws InputError at the record's line: "<file>:<line>: column '<name>' value '<field>': <what>", the
  /// field's control characters and bytes outside UTF-8 written as \xNN.
  [[noreturn]] void fail(size_t row, size_t col, const std::string& what) const;

 private:
  std::string file_;
  std::vector<std::string> header_;
  int header_line_ = 1;
  std::string text_;                   // all data fields' text, back to back
  std::vector<uint32_t> field_begin_;  // field i is text_[field_begin_[i], field_begin_[i+1])
  std::vector<int> row_line_;
};

}  // namespace lpsim

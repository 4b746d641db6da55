#pragma once
// A buffered text sink for the SUMO-format outputs: plain text, or gzip when the file name ends in ".gz".
// Numbers are formatted with std::to_chars straight into the buffer (no iostreams), because FCD output can
// run to millions of records. Fixed-decimal output rounds the exact binary value like printf("%.2f"), which
// is what SUMO's std::fixed/setprecision output gives, so the same double yields the same text.
#include <cstdint>
#include <string>
#include <string_view>

namespace lpsim {

class OutputFile {
 public:
  /// Creates (truncates) `path`. A file that cannot be created is an InputError naming it.
  explicit OutputFile(std::string path);
  /// A resumed run's output: `path` as a saved run left it, cut back to its first `continue_at` bytes (a
  /// continue_point() of that run) and written on from there, a gzip file in a gzip member of its own. An
  /// InputError naming the file when it is missing or shorter than that.
  OutputFile(std::string path, uint64_t continue_at);
  /// Closes the file; errors during this implicit close are swallowed (call close() to see them).
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  const std::string& path() const { return path_; }
  bool is_open() const { return plain_ != nullptr || gz_ != nullptr; }
  bool gzipped() const { return gz_ != nullptr; }
  /// Hands everything written so far to the file and returns the file's length then, where a resumed run
  /// continues it. A gzip file's member ends there, and the text goes on in a new one: concatenated members
  /// decompress as one text (gzip's format; zlib, Python and SUMO read them so), which the run's text is,
  /// saved or not. InputError on failure.
  uint64_t continue_point();

  void text(std::string_view s);
  void put(char c);
  /// Text with the five XML special characters escaped (for ids inside attribute values).
  void escaped(std::string_view s);
  /// Fixed-point with `decimals` digits after the point; NaN and infinities are written as SUMO would
  /// print them through iostreams ("nan", "inf", "-inf").
  void fixed(double v, int decimals = 2);
  /// SUMO's OutputDevice::realString: "0" for zero, fixed-point with `precision` decimals from 10^-precision
  /// up, else scientific with 6 digits after the point ("7.199424e-03"; negative values too).
  void real(double v, int precision);
  void integer(int64_t v);
  void unsigned_integer(uint64_t v);

  /// ` name="value"` helpers for XML attributes.
  void attr(std::string_view name, std::string_view value);  // value is escaped
  void attr_fixed(std::string_view name, double v, int decimals = 2);
  void attr_int(std::string_view name, int64_t v);
  void attr_real(std::string_view name, double v, int precision);

  /// Hands everything written so far to the operating system, so that the file holds it even if the
  /// process is killed next (a gzip stream is flushed to a byte boundary: its data so far decompresses,
  /// at a small cost in compression). For points a reader may want to recover, such as a closed
  /// edgeData interval, not for every record: each call is a system call. InputError on failure.
  void flush();
  /// Writes the buffer out and closes the file; write or close failures are an InputError naming it.
  /// Calling it again does nothing.
  void close();

 private:
  void flush_buffer();
  void reserve(size_t n) {
    if (buffer_.size() - used_ < n) flush_buffer();
  }

  std::string path_;
  void* plain_ = nullptr;  // FILE*
  void* gz_ = nullptr;     // gzFile
  std::string buffer_;
  size_t used_ = 0;
  uint64_t written_ = 0;  // handed to the file (a plain file's length)
};

/// Writes the XML declaration, a provenance comment and the opening root tag carrying SUMO's schema
/// reference (xsd_file is e.g. "fcd_file.xsd"), exactly as SUMO starts its outputs.
void write_sumo_xml_header(OutputFile& out, std::string_view root, std::string_view xsd_file);

}  // namespace lpsim

#include "converters/output_file.hpp"

#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "converters/fixed_decimal.hpp"
#include "core/error.hpp"

namespace lpsim {

namespace {

// Large enough that a write call moves a lot at once, small enough that its pages (each touched once, a page
// fault apiece) are few: a 1 MiB buffer cost 256 page faults per output file.
constexpr size_t kBufferBytes = size_t{1} << 17;
// Longest fixed-point text we ever produce: sign, 309 integer digits of DBL_MAX, point, decimals.
constexpr size_t kMaxNumberChars = 330;

bool ends_with_gz(std::string_view path) { return path.size() >= 3 && path.substr(path.size() - 3) == ".gz"; }

std::string system_reason() { return errno != 0 ? std::strerror(errno) : "unknown error"; }

}  // namespace

OutputFile::OutputFile(std::string path) : path_(std::move(path)), buffer_(kBufferBytes, '\0') {
  errno = 0;
  if (ends_with_gz(path_)) {
    gzFile gz = gzopen(path_.c_str(), "wb6");
    if (gz == nullptr) throw InputError(SourceLoc{path_, 0}, "cannot create output file: " + system_reason());
    gzbuffer(gz, 256 * 1024);
    gz_ = gz;
  } else {
    std::FILE* f = std::fopen(path_.c_str(), "wb");
    if (f == nullptr) throw InputError(SourceLoc{path_, 0}, "cannot create output file: " + system_reason());
    plain_ = f;
  }
}

OutputFile::OutputFile(std::string path, uint64_t continue_at)
    : path_(std::move(path)), buffer_(kBufferBytes, '\0'), written_(continue_at) {
  if (ends_with_gz(path_)) {
    errno = 0;
    struct stat st {};
    if (::stat(path_.c_str(), &st) != 0)
      throw InputError(SourceLoc{path_, 0}, "cannot continue output file: " + system_reason());
    if (static_cast<uint64_t>(st.st_size) < continue_at)
      throw InputError(SourceLoc{path_, 0}, "shorter than the saved run left it (" +
                                                std::to_string(continue_at) +
                                                " bytes): not the output of the run that saved the state");
    // Cut back to the end of the member the save ended, then a new member appended.
    if (::truncate(path_.c_str(), static_cast<off_t>(continue_at)) != 0)
      throw InputError(SourceLoc{path_, 0}, "cannot continue output file: " + system_reason());
    gzFile gz = gzopen(path_.c_str(), "ab6");
    if (gz == nullptr)
      throw InputError(SourceLoc{path_, 0}, "cannot continue output file: " + system_reason());
    gzbuffer(gz, 256 * 1024);
    gz_ = gz;
    return;
  }
  errno = 0;
  std::FILE* f = std::fopen(path_.c_str(), "r+b");
  if (f == nullptr) throw InputError(SourceLoc{path_, 0}, "cannot continue output file: " + system_reason());
  plain_ = f;
  errno = 0;
  if (std::fseek(f, 0, SEEK_END) != 0 || std::ftell(f) < static_cast<long>(continue_at))
    throw InputError(SourceLoc{path_, 0}, "shorter than the saved run left it (" +
                                              std::to_string(continue_at) +
                                              " bytes): not the output of the run that saved the state");
  if (ftruncate(fileno(f), static_cast<off_t>(continue_at)) != 0 ||
      std::fseek(f, static_cast<long>(continue_at), SEEK_SET) != 0)
    throw InputError(SourceLoc{path_, 0}, "cannot continue output file: " + system_reason());
}

OutputFile::~OutputFile() {
  try {
    close();
  } catch (const InputError&) {
    // A destructor must not throw; callers that care call close() themselves.
  }
}

void OutputFile::flush_buffer() {
  if (used_ == 0) return;
  bool ok = true;
  errno = 0;
  if (gz_ != nullptr) {
    ok = gzwrite(static_cast<gzFile>(gz_), buffer_.data(), static_cast<unsigned>(used_)) ==
         static_cast<int>(used_);
  } else if (plain_ != nullptr) {
    ok = std::fwrite(buffer_.data(), 1, used_, static_cast<std::FILE*>(plain_)) == used_;
  }
  written_ += used_;
  used_ = 0;
  if (!ok) throw InputError(SourceLoc{path_, 0}, "cannot write output file: " + system_reason());
}

void OutputFile::flush() {
  if (!is_open()) return;
  flush_buffer();
  errno = 0;
  const bool ok = gz_ != nullptr ? gzflush(static_cast<gzFile>(gz_), Z_SYNC_FLUSH) == Z_OK
                                 : std::fflush(static_cast<std::FILE*>(plain_)) == 0;
  if (!ok) throw InputError(SourceLoc{path_, 0}, "cannot write output file: " + system_reason());
}

uint64_t OutputFile::continue_point() {
  if (!is_open()) throw std::logic_error(path_ + ": continue_point() after close()");
  flush_buffer();
  errno = 0;
  if (gz_ == nullptr) {
    if (std::fflush(static_cast<std::FILE*>(plain_)) != 0)
      throw InputError(SourceLoc{path_, 0}, "cannot write output file: " + system_reason());
    return written_;
  }
  struct stat st {};
  if (gzflush(static_cast<gzFile>(gz_), Z_FINISH) != Z_OK || ::stat(path_.c_str(), &st) != 0)
    throw InputError(SourceLoc{path_, 0}, "cannot write output file: " + system_reason());
  return static_cast<uint64_t>(st.st_size);
}

void OutputFile::close() {
  if (!is_open()) return;
  std::string failure;
  try {
    flush_buffer();
  } catch (const InputError& e) {
    failure = e.what();
  }
  errno = 0;
  if (gz_ != nullptr) {
    if (gzclose(static_cast<gzFile>(gz_)) != Z_OK && failure.empty())
      failure = path_ + ": cannot close output file: " + system_reason();
    gz_ = nullptr;
  } else {
    if (std::fclose(static_cast<std::FILE*>(plain_)) != 0 && failure.empty())
      failure = path_ + ": cannot close output file: " + system_reason();
    plain_ = nullptr;
  }
  if (!failure.empty()) throw InputError(failure);
}

void OutputFile::text(std::string_view s) {
  while (!s.empty()) {
    if (used_ == buffer_.size()) flush_buffer();
    size_t n = std::min(s.size(), buffer_.size() - used_);
    std::memcpy(buffer_.data() + used_, s.data(), n);
    used_ += n;
    s.remove_prefix(n);
  }
}

void OutputFile::put(char c) {
  reserve(1);
  buffer_[used_++] = c;
}

void OutputFile::escaped(std::string_view s) {
  size_t plain_from = 0;
  for (size_t i = 0; i < s.size(); ++i) {
    const char* entity = nullptr;
    switch (s[i]) {
      case '&':
        entity = "&amp;";
        break;
      case '<':
        entity = "&lt;";
        break;
      case '>':
        entity = "&gt;";
        break;
      case '"':
        entity = "&quot;";
        break;
      case '\'':
        entity = "&apos;";
        break;
      default:
        continue;
    }
    text(s.substr(plain_from, i - plain_from));
    text(entity);
    plain_from = i + 1;
  }
  text(s.substr(plain_from));
}

void OutputFile::fixed(double v, int decimals) {
  if (!std::isfinite(v)) {
    text(std::isnan(v) ? "nan" : (v > 0 ? "inf" : "-inf"));
    return;
  }
  reserve(kMaxNumberChars);
  char* begin = buffer_.data() + used_;
  char* end = write_fixed_decimal(begin, v, decimals);
  if (end == nullptr)
    end = std::to_chars(begin, buffer_.data() + buffer_.size(), v, std::chars_format::fixed, decimals).ptr;
  used_ += static_cast<size_t>(end - begin);
}

void OutputFile::real(double v, int precision) {
  if (v == 0) return put('0');
  if (!(v >= std::pow(10.0, -precision))) {  // below the precision (or negative): 6 significant digits
    reserve(kMaxNumberChars);
    char* begin = buffer_.data() + used_;
    used_ += static_cast<size_t>(
        std::to_chars(begin, buffer_.data() + buffer_.size(), v, std::chars_format::scientific, 6).ptr -
        begin);
    return;
  }
  fixed(v, precision);
}

void OutputFile::attr_real(std::string_view name, double v, int precision) {
  put(' ');
  text(name);
  text("=\"");
  real(v, precision);
  put('"');
}

void OutputFile::integer(int64_t v) {
  reserve(24);
  char* begin = buffer_.data() + used_;
  auto result = std::to_chars(begin, buffer_.data() + buffer_.size(), v);
  used_ += static_cast<size_t>(result.ptr - begin);
}

void OutputFile::unsigned_integer(uint64_t v) {
  reserve(24);
  char* begin = buffer_.data() + used_;
  auto result = std::to_chars(begin, buffer_.data() + buffer_.size(), v);
  used_ += static_cast<size_t>(result.ptr - begin);
}

void OutputFile::attr(std::string_view name, std::string_view value) {
  put(' ');
  text(name);
  text("=\"");
  escaped(value);
  put('"');
}

void OutputFile::attr_fixed(std::string_view name, double v, int decimals) {
  put(' ');
  text(name);
  text("=\"");
  fixed(v, decimals);
  put('"');
}

void OutputFile::attr_int(std::string_view name, int64_t v) {
  put(' ');
  text(name);
  text("=\"");
  integer(v);
  put('"');
}

void write_sumo_xml_header(OutputFile& out, std::string_view root, std::string_view xsd_file) {
  out.text("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n\n<!-- generated by LPSim -->\n\n<");
  out.text(root);
  out.text(
      " xmlns:xsi=\"http://www.w3.org/2001/XMLSchema-instance\" "
      "xsi:noNamespaceSchemaLocation=\"http://sumo.dlr.de/xsd/");
  out.text(xsd_file);
  out.text("\">\n");
}

}  // namespace lpsim

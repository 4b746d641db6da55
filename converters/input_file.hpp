#pragma once
// Reads a file's bytes in chunks, gunzipping it when it starts with the gzip magic (whatever its name),
// so readers take .xml and .xml.gz alike.
#include <cstddef>
#include <string>

#include "core/error.hpp"

namespace lpsim {

class InputFile {
 public:
  /// Opens `path`; a missing, unreadable, non-regular or empty file is an InputError.
  explicit InputFile(const std::string& path);
  ~InputFile();
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;

  /// Reads up to `size` bytes into `out`; 0 at the end of the file. A read or decompression error
  /// (a corrupt or truncated .gz) is an InputError.
  size_t read(char* out, size_t size);

 private:
  std::string path_;
  void* file_ = nullptr;  // FILE* of a plain file
  void* gz_ = nullptr;    // gzFile of a gzip file
};

}  // namespace lpsim

// A fresh directory for one test's files, removed with everything in it when the TempDir goes: one place
// for what every file-writing test needs, unique (mkdtemp) even when test processes run in parallel.
#pragma once

#include <stdlib.h>

#include <cerrno>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <system_error>

namespace lpsim::test {

class TempDir {
 public:
  // Creates <temp_directory_path()>/<prefix>_XXXXXX; throws std::runtime_error where that fails.
  explicit TempDir(const std::string& prefix = "lpsim") {
    const std::string pattern = (std::filesystem::temp_directory_path() / (prefix + "_XXXXXX")).string();
    std::string name = pattern;  // mkdtemp replaces the X's in place
    if (mkdtemp(name.data()) == nullptr) {
      const std::error_code error(errno, std::generic_category());
      throw std::runtime_error("TempDir: cannot create " + pattern + ": " + error.message());
    }
    path_ = name;
  }
  ~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }

  // Writes `text` (exact bytes) to the file `name` in the directory; returns the file's full path.
  std::string write(const std::string& name, const std::string& text) const {
    const std::filesystem::path file = path_ / name;
    std::ofstream(file, std::ios::binary) << text;
    return file.string();
  }

 private:
  std::filesystem::path path_;
};

}  // namespace lpsim::test

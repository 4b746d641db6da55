#include "input_file.hpp"

#include <sys/stat.h>
#include <zlib.h>

#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstring>

namespace lpsim {

InputFile::InputFile(const std::string& path) : path_(path) {
  struct stat st {};
  if (stat(path.c_str(), &st) != 0) throw InputError(SourceLoc{path, 0}, "cannot open file (missing?)");
  if (!S_ISREG(st.st_mode)) throw InputError(SourceLoc{path, 0}, "not a regular file");
  if (st.st_size == 0) throw InputError(SourceLoc{path, 0}, "file is empty");
  FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) throw InputError(SourceLoc{path, 0}, std::string("cannot read file: ") + std::strerror(errno));
  unsigned char magic[2] = {0, 0};
  const size_t got = std::fread(magic, 1, 2, f);
  if (got == 2 && magic[0] == 0x1f && magic[1] == 0x8b) {
    std::fclose(f);
    gzFile gz = gzopen(path.c_str(), "rb");
    if (!gz) throw InputError(SourceLoc{path, 0}, "cannot open gzip file");
    gzbuffer(gz, 256 * 1024);
    gz_ = gz;
    return;
  }
  std::rewind(f);
  file_ = f;
}

InputFile::~InputFile() {
  if (file_) std::fclose(static_cast<FILE*>(file_));
  if (gz_) gzclose(static_cast<gzFile>(gz_));
}

size_t InputFile::read(char* out, size_t size) {
  if (file_) {
    FILE* f = static_cast<FILE*>(file_);
    const size_t got = std::fread(out, 1, size, f);
    if (got == 0 && std::ferror(f)) throw InputError(SourceLoc{path_, 0}, "read error");
    return got;
  }
  gzFile gz = static_cast<gzFile>(gz_);
  const int got = gzread(gz, out, static_cast<unsigned>(size > INT_MAX ? INT_MAX : size));
  if (got < 0) {
    int code = 0;
    const char* why = gzerror(gz, &code);
    throw InputError(SourceLoc{path_, 0}, std::string("cannot decompress: ") + (why ? why : "gzip error"));
  }
  return static_cast<size_t>(got);
}

}  // namespace lpsim

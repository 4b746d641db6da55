#pragma once
// FNV-1a, 64 bits, over plain values as the host lays them out: the digests that tie a checkpoint to its
// scenario, its build's layout and its partition (read back by the same build only).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace lpsim {

class Fnv {
 public:
  void bytes(const void* p, size_t n) {
    const auto* b = static_cast<const uint8_t*>(p);
    for (size_t i = 0; i < n; ++i) h_ = (h_ ^ b[i]) * 1099511628211ull;
  }
  template <class T>
  void value(const T& v) {
    bytes(&v, sizeof v);
  }
  template <class T>
  void array(const std::vector<T>& v) {
    value(uint64_t{v.size()});
    bytes(v.data(), v.size() * sizeof(T));
  }
  void text(const std::string& s) {
    value(uint64_t{s.size()});
    bytes(s.data(), s.size());
  }
  uint64_t get() const { return h_; }

 private:
  uint64_t h_ = 14695981039346656037ull;
};

}  // namespace lpsim

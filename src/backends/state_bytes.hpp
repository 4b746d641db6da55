#pragma once
// A backend's run state as bytes and back (Stepper::save_state, load_state): arrays of plain values, each a
// count and its elements in the host's representation, read back by the same build.
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace lpsim {

class StateBytesOut {
 public:
  template <class T>
  void value(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    put(&v, sizeof(T));
  }
  template <class T>
  void array(const T* data, uint64_t n) {
    static_assert(std::is_trivially_copyable_v<T>);
    value(n);
    put(data, n * sizeof(T));
  }
  template <class T>
  void array(const std::vector<T>& v) {
    array(v.data(), v.size());
  }
  std::vector<uint8_t>& bytes() { return bytes_; }

 private:
  void put(const void* p, size_t n) {
    const auto* b = static_cast<const uint8_t*>(p);
    bytes_.insert(bytes_.end(), b, b + n);
  }
  std::vector<uint8_t> bytes_;
};

class StateBytesIn {
 public:
  explicit StateBytesIn(const std::vector<uint8_t>& in) : in_(in) {}
  template <class T>
  void value(T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    get(&v, sizeof(T));
  }
  /// Exactly n elements into data (an array whose length the backend's setup fixes).
  template <class T>
  void array(T* data, uint64_t n) {
    static_assert(std::is_trivially_copyable_v<T>);
    uint64_t got = 0;
    value(got);
    if (got != n)
      throw std::runtime_error("backend state: an array of " + std::to_string(got) + " where this run has " +
                               std::to_string(n) + " (another scenario or other options)");
    get(data, n * sizeof(T));
  }
  /// A vector of the saved length (`fixed`: it must have that length already).
  template <class T>
  void array(std::vector<T>& v, bool fixed) {
    static_assert(std::is_trivially_copyable_v<T>);
    uint64_t n = 0;
    const size_t at = at_;
    value(n);
    at_ = at;
    if (!fixed) {
      if (n > (in_.size() - at_) / sizeof(T))
        throw std::runtime_error("backend state: an array past its end");
      v.resize(n);
    }
    array(v.data(), v.size());
  }
  bool done() const { return at_ == in_.size(); }

 private:
  void get(void* p, size_t n) {
    if (in_.size() - at_ < n) throw std::runtime_error("backend state: it ends inside a value");
    if (n > 0) std::memcpy(p, in_.data() + at_, n);
    at_ += n;
  }
  const std::vector<uint8_t>& in_;
  size_t at_ = 0;
};

}  // namespace lpsim

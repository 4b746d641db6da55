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

/// Bytes that are mostly zeros (a lane map, per-lane counters) as only the stretches between runs of 16 or
/// more zero bytes: their count, then each stretch's offset, length and bytes. Appended to `out`.
inline void put_zero_runs(std::vector<uint8_t>& out, const void* data, uint64_t size) {
  constexpr uint64_t kZeroRun = 16;
  const auto* b = static_cast<const uint8_t*>(data);
  auto put = [&out](const void* p, size_t n) {
    const auto* c = static_cast<const uint8_t*>(p);
    out.insert(out.end(), c, c + n);
  };
  const size_t count_at = out.size();
  uint64_t stretches = 0;
  put(&stretches, sizeof stretches);
  uint64_t at = 0;
  while (at < size) {
    // Zeros skipped a word at a time: a lane map is hundreds of megabytes of them.
    while (at < size && (at & 7) != 0 && b[at] == 0) ++at;
    for (uint64_t word = 0; at + 8 <= size; at += 8) {
      std::memcpy(&word, b + at, 8);
      if (word != 0) break;
    }
    while (at < size && b[at] == 0) ++at;
    if (at == size) break;
    uint64_t end = at, zeros = 0;
    while (end < size && zeros < kZeroRun) zeros = b[end++] == 0 ? zeros + 1 : 0;
    end -= zeros;
    const uint64_t length = end - at;
    put(&at, sizeof at);
    put(&length, sizeof length);
    put(b + at, length);
    ++stretches;
    at = end;
  }
  std::memcpy(out.data() + count_at, &stretches, sizeof stretches);
}

template <class T>
bool all_zero_bytes(const T& v) {
  unsigned char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  for (const unsigned char c : b)
    if (c != 0) return false;
  return true;
}

/// XORs each of the n elements at data with `usual`, byte by byte: an array whose elements are mostly `usual`
/// becomes mostly zeros, and back.
template <class T>
void xor_each(T* data, uint64_t n, const T& usual) {
  static_assert(std::is_trivially_copyable_v<T>);
  unsigned char pattern[sizeof(T)];
  std::memcpy(pattern, &usual, sizeof(T));
  auto* b = reinterpret_cast<unsigned char*>(data);
  for (uint64_t i = 0; i < n; ++i)
    for (size_t j = 0; j < sizeof(T); ++j) b[i * sizeof(T) + j] ^= pattern[j];
}

/// Reads what put_zero_runs wrote from `in` (`available` bytes) into `size` bytes at data; returns the bytes
/// it read. std::runtime_error when they do not fit.
inline size_t get_zero_runs(const uint8_t* in, size_t available, void* data, uint64_t size) {
  auto* b = static_cast<uint8_t*>(data);
  if (size > 0) std::memset(b, 0, size);
  size_t at = 0;
  auto get = [&](void* p, uint64_t n) {
    if (available - at < n) throw std::runtime_error("state: it ends inside a stretch of nonzero bytes");
    if (n > 0) std::memcpy(p, in + at, n);
    at += n;
  };
  uint64_t stretches = 0;
  get(&stretches, sizeof stretches);
  for (uint64_t s = 0; s < stretches; ++s) {
    uint64_t offset = 0, length = 0;
    get(&offset, sizeof offset);
    get(&length, sizeof length);
    if (offset > size || length > size - offset) throw std::runtime_error("state: a stretch past its array");
    get(b + offset, length);
  }
  return at;
}

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
  /// An array that is mostly zeros (a lane map, per-lane counters): put_zero_runs.
  template <class T>
  void sparse(const T* data, uint64_t n) {
    static_assert(std::is_trivially_copyable_v<T>);
    value(n);
    put_zero_runs(bytes_, data, n * sizeof(T));
  }
  template <class T>
  void sparse(const std::vector<T>& v) {
    sparse(v.data(), v.size());
  }
  /// An array whose elements are mostly `usual` (a lane's "none"), as the stretches where they differ.
  template <class T>
  void sparse(const T* data, uint64_t n, const T& usual) {
    if (all_zero_bytes(usual)) return sparse(data, n);  // no copy of a lane map
    std::vector<T> x(data, data + n);
    xor_each(x.data(), n, usual);
    sparse(x.data(), n);
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
    expect_length(n);
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
  /// What StateBytesOut::sparse wrote, into exactly n elements at data.
  template <class T>
  void sparse(T* data, uint64_t n) {
    static_assert(std::is_trivially_copyable_v<T>);
    expect_length(n);
    at_ += get_zero_runs(in_.data() + at_, in_.size() - at_, data, n * sizeof(T));
  }
  template <class T>
  void sparse(std::vector<T>& v) {
    sparse(v.data(), v.size());
  }
  /// What StateBytesOut::sparse wrote of an array mostly `usual`.
  template <class T>
  void sparse(T* data, uint64_t n, const T& usual) {
    sparse(data, n);
    if (!all_zero_bytes(usual)) xor_each(data, n, usual);
  }
  /// The length of the next array, which is still to be read.
  uint64_t next_length() {
    uint64_t n = 0;
    const size_t at = at_;
    value(n);
    at_ = at;
    return n;
  }
  bool done() const { return at_ == in_.size(); }

 private:
  void expect_length(uint64_t n) {
    uint64_t got = 0;
    value(got);
    if (got != n)
      throw std::runtime_error("backend state: an array of " + std::to_string(got) + " where this run has " +
                               std::to_string(n) + " (another scenario or other options)");
  }
  void get(void* p, size_t n) {
    if (in_.size() - at_ < n) throw std::runtime_error("backend state: it ends inside a value");
    if (n > 0) std::memcpy(p, in_.data() + at_, n);
    at_ += n;
  }
  const std::vector<uint8_t>& in_;
  size_t at_ = 0;
};

}  // namespace lpsim

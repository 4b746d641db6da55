#pragma once
// Plain values and arrays of them as the bytes of a round, and back. Both ends run the same build
// (Transport::check_same_build), so values travel in the host's own representation.
#include <cstring>
#include <stdexcept>
#include <type_traits>
#include <vector>

#include "transport/transport.hpp"

namespace lpsim {

class ByteWriter {
 public:
  explicit ByteWriter(Bytes& out) : out_(out) {}
  template <class T>
  void put(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    const auto* b = reinterpret_cast<const uint8_t*>(&v);
    out_.insert(out_.end(), b, b + sizeof(T));
  }
  /// A count, then the elements.
  template <class T>
  void put_array(const std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    put<uint64_t>(v.size());
    const auto* b = reinterpret_cast<const uint8_t*>(v.data());
    out_.insert(out_.end(), b, b + v.size() * sizeof(T));
  }

 private:
  Bytes& out_;
};

class ByteReader {
 public:
  explicit ByteReader(const Bytes& in) : in_(in) {}
  template <class T>
  T get() {
    static_assert(std::is_trivially_copyable_v<T>);
    need(sizeof(T));
    T v;
    std::memcpy(&v, in_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return v;
  }
  template <class T>
  std::vector<T> get_array() {
    const uint64_t n = get<uint64_t>();
    if (n > (in_.size() - at_) / sizeof(T)) throw std::runtime_error("a round's buffer ends inside an array");
    std::vector<T> v(n);
    if (n > 0) std::memcpy(v.data(), in_.data() + at_, n * sizeof(T));
    at_ += n * sizeof(T);
    return v;
  }
  bool done() const { return at_ == in_.size(); }

 private:
  void need(size_t n) const {
    if (in_.size() - at_ < n) throw std::runtime_error("a round's buffer ends inside a value");
  }
  const Bytes& in_;
  size_t at_ = 0;
};

}  // namespace lpsim

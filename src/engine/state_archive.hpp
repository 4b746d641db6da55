#pragma once
// The engine state's fields as bytes and back, for checkpoints. Each piece of state lists its fields once, in
// `template <class A> void visit_state(A& a)`, calling a(field) for each; the writer (StateOut) and the
// reader (StateIn) walk that one list, so the two cannot disagree. A field is a plain value, a vector of
// plain values or of pieces with their own list, a map from plain keys to plain values (in key order), or a
// piece. Values are written in the host's representation: a state is read back by the same build (the
// checkpoint file's header says which).
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <unordered_map>
#include <utility>
#include <vector>

#include "backends/state_bytes.hpp"

namespace lpsim {

template <class T, class A>
concept VisitsState = requires(T& t, A& a) {
  t.visit_state(a);
};

class StateOut {
 public:
  static constexpr bool kReads = false;
  template <class T>
  void operator()(T& v) {
    if constexpr (VisitsState<T, StateOut>) {
      v.visit_state(*this);
    } else {
      static_assert(std::is_trivially_copyable_v<T>);
      put(&v, sizeof(T));
    }
  }
  template <class T>
  void operator()(std::vector<T>& v) {
    uint64_t n = v.size();
    (*this)(n);
    if constexpr (VisitsState<T, StateOut>) {
      for (T& x : v) x.visit_state(*this);
    } else {
      static_assert(std::is_trivially_copyable_v<T>);
      put(v.data(), n * sizeof(T));
    }
  }
  template <class K, class V>
  void operator()(std::vector<std::pair<K, V>>& v) {
    std::vector<K> keys;
    std::vector<V> values;
    for (const auto& [k, x] : v) keys.push_back(k), values.push_back(x);
    (*this)(keys);
    (*this)(values);
  }
  template <class K, class V>
  void operator()(std::unordered_map<K, V>& m) {
    std::vector<std::pair<K, V>> sorted(m.begin(), m.end());
    std::sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    (*this)(sorted);
  }
  /// A vector that is mostly zeros, as only its stretches of nonzero bytes (put_zero_runs).
  template <class T>
  void sparse(std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    uint64_t n = v.size();
    (*this)(n);
    put_zero_runs(bytes_, v.data(), n * sizeof(T));
  }
  /// A vector whose elements are mostly `usual` (a lane of -1: none), as the stretches where they differ.
  template <class T>
  void sparse(std::vector<T>& v, const T& usual) {
    std::vector<T> x = v;
    xor_each(x.data(), x.size(), usual);
    sparse(x);
  }
  /// Bytes written as they are (a backend's own state).
  void raw(const std::vector<uint8_t>& b) {
    uint64_t n = b.size();
    (*this)(n);
    put(b.data(), n);
  }

  std::vector<uint8_t>& bytes() { return bytes_; }
  /// A check that fails while writing: the state being saved does not fit its own run.
  [[noreturn]] void fail(const std::string& why) const { throw std::logic_error("saving a state: " + why); }

 private:
  void put(const void* p, size_t n) {
    const auto* b = static_cast<const uint8_t*>(p);
    bytes_.insert(bytes_.end(), b, b + n);
  }
  std::vector<uint8_t> bytes_;
};

class StateIn {
 public:
  static constexpr bool kReads = true;
  /// `what`: how an error names the state (a file's path).
  StateIn(const uint8_t* data, size_t size, std::string what)
      : data_(data), size_(size), what_(std::move(what)) {}

  template <class T>
  void operator()(T& v) {
    if constexpr (VisitsState<T, StateIn>) {
      v.visit_state(*this);
    } else {
      static_assert(std::is_trivially_copyable_v<T>);
      get(&v, sizeof(T));
    }
  }
  template <class T>
  void operator()(std::vector<T>& v) {
    uint64_t n = 0;
    (*this)(n);
    if constexpr (VisitsState<T, StateIn>) {
      if (n > size_ - at_) fail("a list longer than the state");
      v.assign(n, T{});
      for (T& x : v) x.visit_state(*this);
    } else {
      static_assert(std::is_trivially_copyable_v<T>);
      if (n > (size_ - at_) / std::max<size_t>(1, sizeof(T))) fail("an array longer than the state");
      v.resize(n);
      get(v.data(), n * sizeof(T));
    }
  }
  template <class K, class V>
  void operator()(std::vector<std::pair<K, V>>& v) {
    std::vector<K> keys;
    std::vector<V> values;
    (*this)(keys);
    (*this)(values);
    if (keys.size() != values.size()) fail("a list of pairs with more keys than values");
    v.clear();
    for (size_t i = 0; i < keys.size(); ++i) v.emplace_back(keys[i], values[i]);
  }
  template <class K, class V>
  void operator()(std::unordered_map<K, V>& m) {
    std::vector<std::pair<K, V>> sorted;
    (*this)(sorted);
    m.clear();
    m.insert(sorted.begin(), sorted.end());
  }
  template <class T>
  void sparse(std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    uint64_t n = 0;
    (*this)(n);
    if (n > (uint64_t{1} << 40) / std::max<size_t>(1, sizeof(T))) fail("an array too long for any run");
    v.resize(n);
    try {
      at_ += get_zero_runs(data_ + at_, size_ - at_, v.data(), n * sizeof(T));
    } catch (const std::runtime_error& e) {
      fail(e.what());
    }
  }
  template <class T>
  void sparse(std::vector<T>& v, const T& usual) {
    sparse(v);
    xor_each(v.data(), v.size(), usual);
  }
  void raw(std::vector<uint8_t>& b) { (*this)(b); }

  bool done() const { return at_ == size_; }
  const std::string& what() const { return what_; }
  [[noreturn]] void fail(const std::string& why) const {
    throw std::runtime_error(what_ + ": " + why + " at byte " + std::to_string(at_));
  }

 private:
  void get(void* p, size_t n) {
    if (size_ - at_ < n) fail("the state ends inside a value");
    if (n > 0) std::memcpy(p, data_ + at_, n);
    at_ += n;
  }
  const uint8_t* data_;
  size_t size_, at_ = 0;
  std::string what_;
};

}  // namespace lpsim

#include "converters/edge_id_interner.hpp"

#include <cstring>
#include <limits>

#include "core/error.hpp"

namespace lpsim {
namespace {

constexpr uint32_t kEmpty = 0xFFFFFFFFu;

// Edge ids are short: eight bytes per multiply, inlined, beats a byte-wise or out-of-line hash here.
uint64_t hash_id(std::string_view id) {
  uint64_t h = 0x9E3779B97F4A7C15ull ^ id.size();
  const char* p = id.data();
  size_t n = id.size();
  auto mix = [&h](uint64_t w) {
    h = (h ^ w) * 0xBF58476D1CE4E5B9ull;
    h ^= h >> 29;
  };
  for (; n >= 8; n -= 8, p += 8) {
    uint64_t w;
    std::memcpy(&w, p, 8);
    mix(w);
  }
  if (n > 0) {
    uint64_t w = 0;
    for (size_t i = 0; i < n; ++i) w |= uint64_t{static_cast<unsigned char>(p[i])} << (8 * i);
    mix(w);
  }
  return h ^ (h >> 32);
}

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

}  // namespace

EdgeIdInterner::EdgeIdInterner(std::vector<std::string>& names) : names_(names) {
  offset_.reserve(names.size() + 1);
  offset_.push_back(0);
  for (const auto& n : names) {
    pool_ += n;
    if (pool_.size() >= kEmpty) throw InputError("edge ids of routes longer than 4 GiB in all");
    offset_.push_back(static_cast<uint32_t>(pool_.size()));
  }
  size_t capacity = 1024;
  while (4 * names.size() >= 3 * capacity) capacity *= 2;
  rehash(capacity);
}

void EdgeIdInterner::rehash(size_t capacity) {
  slots_.assign(capacity, Slot{0, kEmpty});
  mask_ = capacity - 1;
  for (uint32_t n = 0; n < names_.size(); ++n) {
    const uint64_t h = hash_id(names_[n]);
    size_t slot = h & mask_;
    while (slots_[slot].name != kEmpty) slot = (slot + 1) & mask_;
    slots_[slot] = {h, n};
  }
}

bool EdgeIdInterner::same(uint32_t name, std::string_view id) const {
  const uint32_t begin = offset_[name];
  if (offset_[name + 1] - begin != id.size()) return false;
  const char* stored = pool_.data() + begin;
  for (size_t i = 0; i < id.size(); ++i)  // ids are short: a loop beats a call to memcmp
    if (stored[i] != id[i]) return false;
  return true;
}

uint32_t EdgeIdInterner::intern(std::string_view id) {
  const uint64_t h = hash_id(id);
  size_t slot = h & mask_;
  for (; slots_[slot].name != kEmpty; slot = (slot + 1) & mask_)
    if (slots_[slot].hash == h && same(slots_[slot].name, id)) return slots_[slot].name;
  if (names_.size() >= kEmpty - 1 || pool_.size() + id.size() >= kEmpty)
    throw InputError("more than 2^32 - 1 distinct edge ids (or bytes of them) in routes");
  const auto index = static_cast<uint32_t>(names_.size());
  names_.emplace_back(id);
  pool_.append(id);
  offset_.push_back(static_cast<uint32_t>(pool_.size()));
  if (4 * names_.size() >= 3 * slots_.size()) {
    rehash(2 * slots_.size());
  } else {
    slots_[slot] = {h, index};
  }
  return index;
}

size_t EdgeIdInterner::intern_list(std::string_view text, std::vector<uint32_t>& refs) {
  const size_t before = refs.size();
  size_t i = 0;
  while (i < text.size()) {
    while (i < text.size() && is_space(text[i])) ++i;
    const size_t start = i;
    while (i < text.size() && !is_space(text[i])) ++i;
    if (i > start) refs.push_back(intern(text.substr(start, i - start)));
  }
  return refs.size() - before;
}

}  // namespace lpsim

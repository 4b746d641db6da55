#include "converters/edge_id_interner.hpp"

#include <functional>
#include <limits>

#include "core/error.hpp"

namespace lpsim {
namespace {

constexpr uint32_t kEmpty = 0xFFFFFFFFu;

uint64_t hash_id(std::string_view id) { return std::hash<std::string_view>{}(id); }

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

}  // namespace

EdgeIdInterner::EdgeIdInterner(std::vector<std::string>& names) : names_(names) {
  size_t capacity = 1024;
  while (capacity < 2 * names.size()) capacity *= 2;
  rehash(capacity);
}

void EdgeIdInterner::rehash(size_t capacity) {
  slot_name_.assign(capacity, kEmpty);
  slot_hash_.assign(capacity, 0);
  mask_ = capacity - 1;
  for (uint32_t n = 0; n < names_.size(); ++n) {
    const uint64_t h = hash_id(names_[n]);
    size_t slot = h & mask_;
    while (slot_name_[slot] != kEmpty) slot = (slot + 1) & mask_;
    slot_name_[slot] = n;
    slot_hash_[slot] = h;
  }
}

uint32_t EdgeIdInterner::intern(std::string_view id) {
  const uint64_t h = hash_id(id);
  size_t slot = h & mask_;
  for (; slot_name_[slot] != kEmpty; slot = (slot + 1) & mask_)
    if (slot_hash_[slot] == h && names_[slot_name_[slot]] == id) return slot_name_[slot];
  if (names_.size() >= kEmpty) throw InputError("more than 2^32 - 1 distinct edge ids in routes");
  const auto index = static_cast<uint32_t>(names_.size());
  names_.emplace_back(id);
  if (2 * names_.size() > slot_name_.size()) {
    rehash(2 * slot_name_.size());
  } else {
    slot_name_[slot] = index;
    slot_hash_[slot] = h;
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

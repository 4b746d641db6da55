#pragma once
// Interning of the edge ids of inline routes while a route file is read: each distinct id is stored once in
// DemandSpec::edge_names and routes become runs of small indices (DemandSpec::edge_refs). Route files repeat
// the same few thousand edge ids millions of times; one string per occurrence costs more memory and time
// than parsing the file.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace lpsim {

class EdgeIdInterner {
 public:
  /// Interns into `names`, indexing the ids already there (a scenario reads several route files).
  explicit EdgeIdInterner(std::vector<std::string>& names);

  /// Index of `id` in names, appending it when new.
  uint32_t intern(std::string_view id);

  /// Interns each id of a list separated by spaces, tabs or newlines (empty pieces dropped, as split_ids)
  /// and appends the indices to `refs`; returns how many were appended.
  size_t intern_list(std::string_view text, std::vector<uint32_t>& refs);

 private:
  void rehash(size_t capacity);

  bool same(uint32_t name, std::string_view id) const;

  std::vector<std::string>& names_;
  // Open addressing: a slot holds an id's hash and its index into names_ (kEmpty when free). The ids are
  // compared in one contiguous copy (pool_ from offset_[n] to offset_[n + 1]): the strings of names_ lie
  // scattered and each probe would miss the cache.
  struct Slot {
    uint64_t hash;
    uint32_t name;
  };
  std::vector<Slot> slots_;
  std::string pool_;
  std::vector<uint32_t> offset_;
  size_t mask_ = 0;
};

}  // namespace lpsim

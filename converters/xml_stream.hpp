#pragma once
// Streaming, safe XML reading on top of libxml2's SAX2 push parser, fed the file's bytes in chunks by
// InputFile: it never builds a document tree nor holds the whole file, reads .xml and .xml.gz alike (in
// UTF-8 or ISO-8859-1), and has entity substitution, DTD loading and network access switched off: entity
// references other than the five predefined ones are refused. Every error it raises names file:line.
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>

#include "core/error.hpp"

namespace lpsim {

class XmlStream {
 public:
  enum class Event { Start, End, Eof };

  /// Opens `path`; a missing, unreadable or empty file is an InputError.
  explicit XmlStream(const std::string& path);
  ~XmlStream();
  XmlStream(const XmlStream&) = delete;
  XmlStream& operator=(const XmlStream&) = delete;

  /// Advances to the next element start or end (an empty element yields Start then End).
  /// Malformed or truncated XML raises InputError at the line where the parser stopped.
  Event next();

  /// Name and depth (root = 0) of the element of the last event.
  const std::string& name() const { return name_; }
  int depth() const { return depth_; }
  int line() const { return line_; }
  const std::string& path() const { return path_; }
  SourceLoc loc() const { return SourceLoc{path_, line_}; }

  /// Attribute access for the element of the last Start event.
  std::optional<std::string> attr(const char* key) const;
  bool has(const char* key) const { return attr(key).has_value(); }
  std::string required(const char* key) const;
  std::string get(const char* key, std::string_view fallback) const;
  /// Strict number: the whole value must parse; NaN and infinities are refused.
  double number(const char* key, double fallback) const;
  double required_number(const char* key) const;
  /// As number(), and additionally refuses negative values.
  double non_negative(const char* key, double fallback) const;
  long long integer(const char* key, long long fallback) const;
  /// Calls visit(name, value) for each attribute of the element of the last Start event, in document order,
  /// without copying: one pass for elements read by the million, and the only way to see unknown attributes.
  /// The views are valid only during the call.
  template <class Visit>
  void for_each_attr(Visit&& visit) const {
    for_each_attr_impl(&visit, [](void* v, std::string_view name, std::string_view value) {
      (*static_cast<std::remove_reference_t<Visit>*>(v))(name, value);
    });
  }

  /// Raises InputError at the current element: "<elem id=...>: message".
  [[noreturn]] void fail(const std::string& message) const;

 private:
  void for_each_attr_impl(void* visit, void (*call)(void*, std::string_view, std::string_view)) const;
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::string path_, name_;
  int depth_ = 0, line_ = 0;
};

/// Strict parse of a whole string as a finite double; nullopt when it is not one.
std::optional<double> parse_double(std::string_view text);
std::optional<long long> parse_integer(std::string_view text);

}  // namespace lpsim

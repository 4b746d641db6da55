#include "xml_stream.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "input_file.hpp"

namespace lpsim {

namespace {

std::string context_label(const XmlStream& xs) {
  std::string label = "<" + xs.name();
  if (auto id = xs.attr("id")) label += " id=\"" + *id + "\"";
  return label + ">";
}

// Byte classes of the tokenizer (XML 1.0 productions, with every byte >= 0x80 taken as a name character:
// UTF-8 sequences are passed through unchecked).
constexpr uint8_t kSpace = 1, kNameStart = 2, kName = 4;

constexpr std::array<uint8_t, 256> byte_classes() {
  std::array<uint8_t, 256> t{};
  for (int c : {' ', '\t', '\n', '\r'}) t[c] = kSpace;
  for (int c = 'a'; c <= 'z'; ++c) t[c] = kNameStart | kName;
  for (int c = 'A'; c <= 'Z'; ++c) t[c] = kNameStart | kName;
  for (int c = 0x80; c < 256; ++c) t[c] = kNameStart | kName;
  t['_'] = t[':'] = kNameStart | kName;
  for (int c = '0'; c <= '9'; ++c) t[c] = kName;
  t['-'] = t['.'] = kName;
  return t;
}
constexpr std::array<uint8_t, 256> kClass = byte_classes();

bool is_space(char c) { return kClass[static_cast<uint8_t>(c)] & kSpace; }
bool is_name_start(char c) { return kClass[static_cast<uint8_t>(c)] & kNameStart; }
bool is_name(char c) { return kClass[static_cast<uint8_t>(c)] & kName; }

void append_utf8(std::string& out, uint32_t cp) {
  if (cp < 0x80) {
    out.push_back(static_cast<char>(cp));
  } else if (cp < 0x800) {
    out.push_back(static_cast<char>(0xC0 | (cp >> 6)));
    out.push_back(static_cast<char>(0x80 | (cp & 0x3F)));
  } else if (cp < 0x10000) {
    out.push_back(static_cast<char>(0xE0 | (cp >> 12)));
    out.push_back(static_cast<char>(0x80 | ((cp >> 6) & 0x3F)));
    out.push_back(static_cast<char>(0x80 | (cp & 0x3F)));
  } else {
    out.push_back(static_cast<char>(0xF0 | (cp >> 18)));
    out.push_back(static_cast<char>(0x80 | ((cp >> 12) & 0x3F)));
    out.push_back(static_cast<char>(0x80 | ((cp >> 6) & 0x3F)));
    out.push_back(static_cast<char>(0x80 | (cp & 0x3F)));
  }
}

bool iequals(std::string_view a, std::string_view b) {
  return a.size() == b.size() &&
         std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) { return (x | 0x20) == (y | 0x20); });
}

}  // namespace

// A pull tokenizer over a buffer of the file, refilled in chunks: an element's start tag is tokenized in
// place (attribute names and plain values are views into the buffer; values with references or line breaks
// are decoded into `decoded`), and text, comments, processing instructions, CDATA and the DOCTYPE are
// skipped. The buffer is refilled only inside next(), so the views of the last event stay valid until the
// next call. A tag cut by the end of the buffer is tokenized again from its '<' after a refill.
//
// What it accepts is well-formed XML 1.0 in UTF-8 (or ISO-8859-1 when the declaration says so), minus
// entity references other than the five predefined ones (refused, as LPSim never substitutes entities).
// It checks what a misread would silently change: tag nesting, attribute syntax and duplicates, references,
// a single root element, text outside it. It does not check every character class of the productions.
struct XmlStream::Impl {
  struct Attr {
    std::string_view name;  // in the buffer
    const char* raw;        // value in the buffer, or nullptr when decoded
    uint32_t begin, size;   // decoded value in `decoded`
  };
  enum class Status { Done, NeedMore };

  InputFile input;
  std::string path;
  std::vector<char> buf;
  size_t pos = 0, end = 0;  // unread bytes: buf[pos, end)
  bool eof = false;
  size_t line_pos = 0;            // buf offset up to which lines are counted
  int line = 1;                   // line of buf[line_pos]
  bool latin1 = false;            // declared ISO-8859-1: values are converted to UTF-8
  bool started = false;           // the first read done (and a byte order mark looked for)
  bool at_file_start = true;      // nothing but a byte order mark read yet: an XML declaration may come
  std::vector<std::string> open;  // names of the open elements, root first
  bool root_seen = false;
  bool pending_end = false;  // an empty element's End is due
  // The previous event was a non-empty element's start: an end tag right after it must close that element,
  // and is reported at the start tag's line (as SUMO's parser does for an element without children).
  bool last_was_start = false;
  int last_start_line = 0;
  int last_line = 0;  // line reported for the end tag just read
  std::vector<Attr> attrs;
  std::string decoded;

  explicit Impl(const std::string& p) : input(p), path(p) { buf.resize(1 << 18); }

  // Line of buffer offset `at` (>= line_pos): counts the newlines on the way.
  int line_at(size_t at) {
    if (at > line_pos) {
      line += static_cast<int>(std::count(buf.data() + line_pos, buf.data() + at, '\n'));
      line_pos = at;
    }
    return line;
  }

  [[noreturn]] void malformed(size_t at, const std::string& what) {
    throw InputError(SourceLoc{path, line_at(std::min(at, end))}, "malformed XML: " + what);
  }
  [[noreturn]] void entity_reference(size_t at) {
    throw InputError(SourceLoc{path, line_at(at)}, "entity references are not supported");
  }

  // Moves the unread bytes to the front and reads more behind them (growing the buffer when it is full of
  // unread bytes, for a token longer than it). False at the end of the file.
  bool fill() {
    if (eof) return false;
    line_at(pos);
    if (pos > 0) {
      std::memmove(buf.data(), buf.data() + pos, end - pos);
      end -= pos;
      line_pos -= pos;
      pos = 0;
    }
    if (end == buf.size()) buf.resize(buf.size() * 2);
    const size_t got = input.read(buf.data() + end, buf.size() - end);
    if (got == 0) {
      eof = true;
      return false;
    }
    end += got;
    if (!started) {
      started = true;
      check_byte_order_mark();
    }
    return true;
  }

  void check_byte_order_mark() {
    const auto* b = reinterpret_cast<const unsigned char*>(buf.data());
    if (end >= 3 && b[0] == 0xEF && b[1] == 0xBB && b[2] == 0xBF) {
      pos = 3;
      line_pos = 3;
    } else if (end >= 2 && ((b[0] == 0xFE && b[1] == 0xFF) || (b[0] == 0xFF && b[1] == 0xFE))) {
      throw InputError(SourceLoc{path, 1}, "unsupported encoding UTF-16 (LPSim reads UTF-8 and ISO-8859-1)");
    }
  }

  // Decodes the reference at buf[at] ('&') into out; returns the offset past its ';'. Entity references
  // other than the predefined five are refused.
  size_t decode_reference(size_t at, size_t limit, std::string& out) {
    const char* s = buf.data();
    const char* semi = static_cast<const char*>(std::memchr(s + at, ';', std::min(limit, at + 12) - at));
    if (!semi) {
      if (at + 1 < limit && is_name_start(s[at + 1])) entity_reference(at);
      malformed(at, "'&' not followed by a reference (write &amp;)");
    }
    const std::string_view ref(s + at + 1, static_cast<size_t>(semi - (s + at + 1)));
    const size_t after = static_cast<size_t>(semi - s) + 1;
    if (!ref.empty() && ref[0] == '#') {
      uint32_t cp = 0;
      const bool hex = ref.size() > 1 && ref[1] == 'x';
      const std::string_view digits = ref.substr(hex ? 2 : 1);
      auto [p, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), cp, hex ? 16 : 10);
      if (digits.empty() || ec != std::errc() || p != digits.data() + digits.size() || cp == 0 ||
          cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF))
        malformed(at, "invalid character reference '&" + std::string(ref) + ";'");
      append_utf8(out, cp);
      return after;
    }
    if (ref == "amp")
      out.push_back('&');
    else if (ref == "lt")
      out.push_back('<');
    else if (ref == "gt")
      out.push_back('>');
    else if (ref == "quot")
      out.push_back('"');
    else if (ref == "apos")
      out.push_back('\'');
    else if (!ref.empty() && is_name_start(ref[0]))
      entity_reference(at);
    else
      malformed(at, "'&' not followed by a reference (write &amp;)");
    return after;
  }

  // Text between tags: only its references are checked; outside the root element only white space may
  // stand.
  void check_text(size_t from, size_t to) {
    const char* s = buf.data();
    if (open.empty()) {
      for (size_t i = from; i < to; ++i)
        if (!is_space(s[i]))
          malformed(i, root_seen ? "premature end of data or content after the root element (truncated file?)"
                                 : "text before the root element");
      return;
    }
    std::string scratch;
    for (const char* amp = static_cast<const char*>(std::memchr(s + from, '&', to - from)); amp;) {
      const size_t after = decode_reference(static_cast<size_t>(amp - s), to, scratch);
      amp = static_cast<const char*>(std::memchr(s + after, '&', to - after));
    }
  }

  // Offset just past the first `terminator` at or after `from`, or 0 when the buffer holds none yet.
  size_t find_past(size_t from, std::string_view terminator) const {
    const std::string_view rest(buf.data() + from, end - from);
    const size_t at = rest.find(terminator);
    return at == std::string_view::npos ? 0 : from + at + terminator.size();
  }

  // Markup starting "<!" or "<?" at pos: skipped (the XML declaration read for its encoding).
  Status skip_markup() {
    const char* s = buf.data();
    const std::string_view head(s + pos, std::min<size_t>(end - pos, 9));
    size_t past = 0;
    if (head.substr(0, 2) == "<?") {
      past = find_past(pos + 2, "?>");
      if (past && head.substr(0, 5) == "<?xml" && past - pos > 5 && is_space(s[pos + 5])) {
        if (!at_file_start) malformed(pos, "XML declaration not at the start of the file");
        read_declaration(pos, past);
      }
    } else if (head.substr(0, 4) == "<!--") {
      past = find_past(pos + 4, "-->");
    } else if (head.substr(0, 9) == "<![CDATA[") {
      if (open.empty()) malformed(pos, "CDATA outside the root element");
      past = find_past(pos + 9, "]]>");
    } else if (head.size() >= 9 && head.substr(0, 9) == "<!DOCTYPE") {
      if (root_seen) malformed(pos, "DOCTYPE after the root element");
      past = doctype_end(pos + 9);
    } else if (head.size() >= 9 || eof) {
      malformed(pos, "unknown markup '" + std::string(head) + "'");
    }
    if (!past) return Status::NeedMore;
    pos = past;
    return Status::Done;
  }

  // End of a DOCTYPE (its internal subset in brackets, quoted literals and comments skipped), or 0.
  size_t doctype_end(size_t from) const {
    const char* s = buf.data();
    int brackets = 0;
    for (size_t i = from; i < end; ++i) {
      const char c = s[i];
      if (c == '"' || c == '\'') {
        const void* q = std::memchr(s + i + 1, c, end - i - 1);
        if (!q) return 0;
        i = static_cast<size_t>(static_cast<const char*>(q) - s);
      } else if (c == '<' && end - i >= 4 && std::memcmp(s + i, "<!--", 4) == 0) {
        const size_t past = find_past(i + 4, "-->");
        if (!past) return 0;
        i = past - 1;
      } else if (c == '[') {
        ++brackets;
      } else if (c == ']') {
        --brackets;
      } else if (c == '>' && brackets <= 0) {
        return i + 1;
      }
    }
    return 0;
  }

  void read_declaration(size_t from, size_t past) {
    const std::string_view decl(buf.data() + from, past - from);
    const size_t at = decl.find("encoding");
    if (at == std::string_view::npos) return;
    size_t q = decl.find_first_of("\"'", at);
    if (q == std::string_view::npos) malformed(from, "bad encoding declaration");
    const size_t close = decl.find(decl[q], q + 1);
    if (close == std::string_view::npos) malformed(from, "bad encoding declaration");
    const std::string_view enc = decl.substr(q + 1, close - q - 1);
    if (iequals(enc, "UTF-8") || iequals(enc, "UTF8") || iequals(enc, "US-ASCII") || iequals(enc, "ASCII"))
      return;
    if (iequals(enc, "ISO-8859-1") || iequals(enc, "LATIN1") || iequals(enc, "ISO_8859-1") ||
        iequals(enc, "LATIN-1")) {
      latin1 = true;
      return;
    }
    throw InputError(SourceLoc{path, line_at(from)},
                     "unsupported encoding '" + std::string(enc) + "' (LPSim reads UTF-8 and ISO-8859-1)");
  }

  // The end tag at pos. NeedMore when the buffer ends inside it.
  Status end_tag(std::string& name_out) {
    const char* s = buf.data();
    size_t i = pos + 2;
    const size_t name_begin = i;
    while (i < end && is_name(s[i])) ++i;
    const size_t name_end = i;
    while (i < end && is_space(s[i])) ++i;
    if (i >= end) return Status::NeedMore;
    const std::string_view name(s + name_begin, name_end - name_begin);
    if (s[i] != '>' || name.empty() || !is_name_start(name[0])) malformed(pos, "bad end tag");
    if (open.empty()) malformed(pos, "end tag </" + std::string(name) + "> without a start tag");
    if (name != open.back())
      malformed(pos, "opening and ending tag mismatch: " + open.back() + " and " + std::string(name));
    const int l = line_at(i);
    name_out = std::move(open.back());
    open.pop_back();
    last_line = last_was_start ? last_start_line : l;
    pos = i + 1;
    return Status::Done;
  }
  // Decodes a value that holds references, line breaks or (ISO-8859-1) high bytes into `decoded`.
  Attr decode_value(std::string_view name, size_t from, size_t to) {
    const char* s = buf.data();
    const size_t begin = decoded.size();
    for (size_t i = from; i < to;) {
      const char c = s[i];
      if (c == '&') {
        i = decode_reference(i, to, decoded);
      } else if (c == '\r' || c == '\n' || c == '\t') {
        // Attribute-value normalisation: each line break (CR LF as one) and tab reads as a space.
        decoded.push_back(' ');
        i += (c == '\r' && i + 1 < to && s[i + 1] == '\n') ? 2 : 1;
      } else if (latin1 && static_cast<unsigned char>(c) >= 0x80) {
        append_utf8(decoded, static_cast<unsigned char>(c));
        ++i;
      } else {
        decoded.push_back(c);
        ++i;
      }
    }
    return Attr{name, nullptr, static_cast<uint32_t>(begin), static_cast<uint32_t>(decoded.size() - begin)};
  }

  // First offset from i on holding the quote or a byte that needs a look in an attribute value ('&', '<',
  // control characters such as line breaks, and high bytes in ISO-8859-1), or `to` when there is none.
  size_t value_stop(const char* s, size_t i, size_t to, char quote) const {
#if defined(__SSE2__)
    const __m128i q = _mm_set1_epi8(quote), amp = _mm_set1_epi8('&'), lt = _mm_set1_epi8('<');
    const __m128i space = _mm_set1_epi8(' ');
    for (; i + 16 <= to; i += 16) {
      const __m128i x = _mm_loadu_si128(reinterpret_cast<const __m128i*>(s + i));
      // Signed compare: bytes below ' ' and, as negative numbers, bytes >= 0x80 are caught together.
      __m128i hit = _mm_or_si128(_mm_or_si128(_mm_cmpeq_epi8(x, q), _mm_cmpeq_epi8(x, amp)),
                                 _mm_or_si128(_mm_cmpeq_epi8(x, lt), _mm_cmplt_epi8(x, space)));
      int mask = _mm_movemask_epi8(hit);
      if (!latin1) mask &= ~_mm_movemask_epi8(x);  // high bytes are plain UTF-8 unless ISO-8859-1
      if (mask) return i + static_cast<size_t>(__builtin_ctz(static_cast<unsigned>(mask)));
    }
#endif
    for (; i < to; ++i) {
      const auto c = static_cast<unsigned char>(s[i]);
      if (c == static_cast<unsigned char>(quote) || c == '&' || c == '<' || c < ' ' || (latin1 && c >= 0x80))
        return i;
    }
    return to;
  }

  // The start tag at pos: its name and attributes. NeedMore when the buffer ends inside it.
  Status start_tag(std::string& name_out, bool& empty) {
    const char* s = buf.data();
    attrs.clear();
    decoded.clear();
    size_t i = pos + 1;
    if (i >= end) return Status::NeedMore;
    if (!is_name_start(s[i])) malformed(pos, "bad start tag ('<' must start a tag; write &lt; in text)");
    while (i < end && is_name(s[i])) ++i;
    const std::string_view name(s + pos + 1, i - pos - 1);
    bool namespaces = false;
    for (;;) {
      const size_t before_space = i;
      while (i < end && is_space(s[i])) ++i;
      if (i >= end) return Status::NeedMore;
      if (s[i] == '>' || s[i] == '/') {
        if (s[i] == '/') {
          if (i + 1 >= end) return Status::NeedMore;
          if (s[i + 1] != '>') malformed(i, "expected '>' after '/' in <" + std::string(name) + ">");
          empty = true;
          pos = i + 2;
        } else {
          empty = false;
          pos = i + 1;
        }
        break;
      }
      if (i == before_space || !is_name_start(s[i]))
        malformed(i, "bad attribute syntax in <" + std::string(name) + ">");
      const size_t attr_begin = i;
      while (i < end && is_name(s[i])) ++i;
      const std::string_view attr_name(s + attr_begin, i - attr_begin);
      while (i < end && is_space(s[i])) ++i;
      if (i >= end) return Status::NeedMore;
      if (s[i] != '=') malformed(i, "attribute " + std::string(attr_name) + " without a value");
      ++i;
      while (i < end && is_space(s[i])) ++i;
      if (i >= end) return Status::NeedMore;
      const char quote = s[i];
      if (quote != '"' && quote != '\'') malformed(i, "attribute " + std::string(attr_name) + " not quoted");
      const size_t value_begin = ++i;
      // Plain values (the rule) are views; the scan notes what needs decoding.
      bool plain = true;
      for (;; ++i) {
        i = value_stop(s, i, end, quote);
        if (i >= end) return Status::NeedMore;
        const char c = s[i];
        if (c == quote) break;
        if (c == '<') malformed(i, "'<' in the value of attribute " + std::string(attr_name));
        plain = false;
      }
      for (const Attr& a : attrs)
        if (a.name == attr_name) malformed(attr_begin, "Attribute " + std::string(attr_name) + " redefined");
      if (plain)
        attrs.push_back(Attr{attr_name, s + value_begin, 0, static_cast<uint32_t>(i - value_begin)});
      else
        attrs.push_back(decode_value(attr_name, value_begin, i));
      if (attr_name.substr(0, 5) == "xmlns") namespaces = true;
      ++i;
    }
    // Namespace declarations are listed before the other attributes (as libxml2's reader lists them).
    if (namespaces)
      std::stable_partition(attrs.begin(), attrs.end(), [](const Attr& a) {
        return a.name.substr(0, 5) == "xmlns" && (a.name.size() == 5 || a.name[5] == ':');
      });
    name_out.assign(name);
    return Status::Done;
  }

  std::string_view value(const Attr& a) const {
    return a.raw ? std::string_view(a.raw, a.size) : std::string_view(decoded.data() + a.begin, a.size);
  }
};

XmlStream::XmlStream(const std::string& path) : impl_(std::make_unique<Impl>(path)), path_(path) {}

XmlStream::~XmlStream() = default;

XmlStream::Event XmlStream::next() {
  Impl& im = *impl_;
  if (im.pending_end) {
    im.pending_end = false;
    im.attrs.clear();
    im.last_was_start = false;
    depth_ = static_cast<int>(im.open.size());
    return Event::End;  // name_ and line_ are the empty element's
  }
  im.attrs.clear();
  for (;;) {
    const char* lt = im.pos < im.end
                         ? static_cast<const char*>(std::memchr(im.buf.data() + im.pos, '<', im.end - im.pos))
                         : nullptr;
    if (!lt) {
      if (im.fill()) continue;  // text cut by the buffer's end: checked whole once its '<' is in
      im.check_text(im.pos, im.end);
      im.pos = im.end;
      if (!im.open.empty() || !im.root_seen)
        im.malformed(im.end, im.root_seen
                                 ? "premature end of data in <" + im.open.back() + "> (truncated file?)"
                                 : "no root element");
      return Event::Eof;
    }
    const size_t at = static_cast<size_t>(lt - im.buf.data());
    if (at != im.pos) {
      im.at_file_start = false;
      im.check_text(im.pos, at);
      im.pos = at;
    }
    const char next = at + 1 < im.end ? im.buf[at + 1] : '\0';
    Impl::Status status;
    if (at + 1 >= im.end) {
      status = Impl::Status::NeedMore;
    } else if (next == '!' || next == '?') {
      status = im.skip_markup();
      if (status == Impl::Status::Done) {
        im.at_file_start = false;
        continue;
      }
    } else if (next == '/') {
      status = im.end_tag(name_);
      if (status == Impl::Status::Done) {
        im.at_file_start = false;
        depth_ = static_cast<int>(im.open.size());
        line_ = im.last_line;
        im.last_was_start = false;
        return Event::End;
      }
    } else {
      if (im.root_seen && im.open.empty())
        im.malformed(at, "premature end of data or content after the root element (truncated file?)");
      bool empty = false;
      status = im.start_tag(name_, empty);
      if (status == Impl::Status::Done) {
        im.at_file_start = false;
        line_ = im.line_at(im.pos - 1);  // where the start tag ends, as SUMO's parser reports it
        depth_ = static_cast<int>(im.open.size());
        im.root_seen = true;
        if (empty) {
          im.pending_end = true;
        } else {
          im.open.push_back(name_);
          im.last_was_start = true;
          im.last_start_line = line_;
        }
        return Event::Start;
      }
      im.attrs.clear();
    }
    // The buffer ends inside the markup at pos: read on and tokenize it again.
    if (!im.fill()) im.malformed(im.pos, "premature end of data in a tag (truncated file?)");
  }
}

std::optional<std::string> XmlStream::attr(const char* key) const {
  const Impl& im = *impl_;
  const std::string_view k(key);
  for (const Impl::Attr& a : im.attrs)
    if (a.name == k) return std::string(im.value(a));
  return std::nullopt;
}

void XmlStream::for_each_attr_impl(void* visit,
                                   void (*call)(void*, std::string_view, std::string_view)) const {
  const Impl& im = *impl_;
  for (const Impl::Attr& a : im.attrs) call(visit, a.name, im.value(a));
}

std::string XmlStream::required(const char* key) const {
  auto v = attr(key);
  if (!v) fail(std::string("missing attribute '") + key + "'");
  return *v;
}

std::string XmlStream::get(const char* key, std::string_view fallback) const {
  auto v = attr(key);
  return v ? *v : std::string(fallback);
}

double XmlStream::number(const char* key, double fallback) const {
  auto v = attr(key);
  if (!v) return fallback;
  auto d = parse_double(*v);
  if (!d) fail(std::string("attribute '") + key + "' is not a finite number: '" + *v + "'");
  return *d;
}

double XmlStream::required_number(const char* key) const {
  if (!has(key)) fail(std::string("missing attribute '") + key + "'");
  return number(key, 0);
}

double XmlStream::non_negative(const char* key, double fallback) const {
  double d = number(key, fallback);
  if (d < 0 && has(key))
    fail(std::string("attribute '") + key + "' must not be negative: '" + *attr(key) + "'");
  return d;
}

long long XmlStream::integer(const char* key, long long fallback) const {
  auto v = attr(key);
  if (!v) return fallback;
  auto i = parse_integer(*v);
  if (!i) fail(std::string("attribute '") + key + "' is not an integer: '" + *v + "'");
  return *i;
}

void XmlStream::fail(const std::string& message) const {
  throw InputError(loc(), context_label(*this) + ": " + message);
}

std::optional<double> parse_double(std::string_view text) {
  while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
  while (!text.empty() && (text.back() == ' ' || text.back() == '\t')) text.remove_suffix(1);
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  if (text.empty()) return std::nullopt;
  double d = 0;
  auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), d);
  if (ec != std::errc() || ptr != text.data() + text.size() || !std::isfinite(d)) return std::nullopt;
  return d;
}

std::optional<long long> parse_integer(std::string_view text) {
  while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
  while (!text.empty() && (text.back() == ' ' || text.back() == '\t')) text.remove_suffix(1);
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  if (text.empty()) return std::nullopt;
  long long v = 0;
  auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || ptr != text.data() + text.size()) return std::nullopt;
  return v;
}

}  // namespace lpsim

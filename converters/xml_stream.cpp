#include "xml_stream.hpp"

#include <libxml/xmlreader.h>
#include <sys/stat.h>

#include <charconv>
#include <cmath>
#include <cstdio>

namespace lpsim {

namespace {

std::string context_label(const XmlStream& xs) {
  std::string label = "<" + xs.name();
  if (auto id = xs.attr("id")) label += " id=\"" + *id + "\"";
  return label + ">";
}

// libxml2 reports errors through a callback; keep the first message so the exception names the cause.
void remember_error(void* arg, const char* msg, xmlParserSeverities severity, xmlTextReaderLocatorPtr loc) {
  auto* first = static_cast<std::pair<std::string, int>*>(arg);
  if (severity != XML_PARSER_SEVERITY_ERROR && severity != XML_PARSER_SEVERITY_VALIDITY_ERROR) return;
  if (!first->first.empty()) return;
  first->first = msg ? msg : "malformed XML";
  while (!first->first.empty() && (first->first.back() == '\n' || first->first.back() == ' '))
    first->first.pop_back();
  // The locator is the parser context: its input line is where parsing failed (the reader's node line
  // would be the enclosing element's).
  auto* ctxt = reinterpret_cast<xmlParserCtxtPtr>(loc);
  first->second = ctxt && ctxt->input ? ctxt->input->line : xmlTextReaderLocatorLineNumber(loc);
  // The reader reports a file cut short as "extra content"; say what it usually means.
  if (first->first.find("Extra content at the end of the document") != std::string::npos)
    first->first = "premature end of data or content after the root element (truncated file?)";
}

}  // namespace

struct XmlStream::Impl {
  xmlTextReaderPtr reader = nullptr;
  std::pair<std::string, int> first_error;
};

XmlStream::XmlStream(const std::string& path) : impl_(std::make_unique<Impl>()), path_(path) {
  struct stat st {};
  if (stat(path.c_str(), &st) != 0) throw InputError(SourceLoc{path, 0}, "cannot open file (missing?)");
  if (!S_ISREG(st.st_mode)) throw InputError(SourceLoc{path, 0}, "not a regular file");
  if (st.st_size == 0) throw InputError(SourceLoc{path, 0}, "file is empty");
  if (FILE* f = std::fopen(path.c_str(), "rb")) {
    std::fclose(f);
  } else {
    throw InputError(SourceLoc{path, 0}, "cannot read file");
  }
  // No XML_PARSE_NOENT (no entity substitution), no DTDLOAD/DTDVALID, NONET: safe on untrusted input.
  // HUGE lifts libxml2's limits on text size for very large networks, not on entity expansion.
  // BIG_LINES: element line numbers above 65535 stay exact.
  impl_->reader = xmlReaderForFile(path.c_str(), nullptr,
                                   XML_PARSE_NONET | XML_PARSE_HUGE | XML_PARSE_NOCDATA | XML_PARSE_BIG_LINES);
  if (!impl_->reader) throw InputError(SourceLoc{path, 0}, "cannot open as XML");
  xmlTextReaderSetErrorHandler(impl_->reader, remember_error, &impl_->first_error);
}

XmlStream::~XmlStream() {
  if (impl_ && impl_->reader) xmlFreeTextReader(impl_->reader);
}

XmlStream::Event XmlStream::next() {
  if (pending_end_) {
    pending_end_ = false;
    return Event::End;
  }
  for (;;) {
    int rc = xmlTextReaderRead(impl_->reader);
    if (rc == 0) {
      if (!impl_->first_error.first.empty())
        throw InputError(SourceLoc{path_, impl_->first_error.second}, "malformed XML: " + impl_->first_error.first);
      return Event::Eof;
    }
    if (rc < 0) {
      int line = impl_->first_error.second > 0 ? impl_->first_error.second : line_;
      std::string why = impl_->first_error.first.empty() ? "malformed or truncated XML" : impl_->first_error.first;
      throw InputError(SourceLoc{path_, line}, "malformed XML: " + why);
    }
    int type = xmlTextReaderNodeType(impl_->reader);
    if (type == XML_READER_TYPE_ELEMENT) {
      const xmlChar* n = xmlTextReaderConstName(impl_->reader);
      name_ = n ? reinterpret_cast<const char*>(n) : "";
      depth_ = xmlTextReaderDepth(impl_->reader);
      // The parser reads ahead by a buffer, so take the element's own line (exact with XML_PARSE_BIG_LINES).
      long node_line = xmlGetLineNo(xmlTextReaderCurrentNode(impl_->reader));
      line_ = node_line > 0 ? static_cast<int>(node_line) : xmlTextReaderGetParserLineNumber(impl_->reader);
      pending_end_ = xmlTextReaderIsEmptyElement(impl_->reader) == 1;
      return Event::Start;
    }
    if (type == XML_READER_TYPE_END_ELEMENT) {
      const xmlChar* n = xmlTextReaderConstName(impl_->reader);
      name_ = n ? reinterpret_cast<const char*>(n) : "";
      depth_ = xmlTextReaderDepth(impl_->reader);
      line_ = xmlTextReaderGetParserLineNumber(impl_->reader);
      return Event::End;
    }
    if (type == XML_READER_TYPE_ENTITY_REFERENCE)
      throw InputError(SourceLoc{path_, xmlTextReaderGetParserLineNumber(impl_->reader)},
                       "entity references are not supported");
  }
}

std::optional<std::string> XmlStream::attr(const char* key) const {
  xmlChar* v = xmlTextReaderGetAttribute(impl_->reader, reinterpret_cast<const xmlChar*>(key));
  if (!v) return std::nullopt;
  std::string s(reinterpret_cast<const char*>(v));
  xmlFree(v);
  return s;
}

void XmlStream::for_each_attr_impl(void* visit, void (*call)(void*, std::string_view, std::string_view)) const {
  xmlTextReaderPtr r = impl_->reader;
  for (int rc = xmlTextReaderMoveToFirstAttribute(r); rc == 1; rc = xmlTextReaderMoveToNextAttribute(r)) {
    const xmlChar* n = xmlTextReaderConstName(r);
    const xmlChar* v = xmlTextReaderConstValue(r);
    call(visit, n ? reinterpret_cast<const char*>(n) : "", v ? reinterpret_cast<const char*>(v) : "");
  }
  xmlTextReaderMoveToElement(r);
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
  if (d < 0 && has(key)) fail(std::string("attribute '") + key + "' must not be negative: '" + *attr(key) + "'");
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

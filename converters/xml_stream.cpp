#include "xml_stream.hpp"

#include <libxml/SAX2.h>
#include <libxml/parser.h>
#include <libxml/xmlIO.h>
#include <sys/stat.h>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

namespace lpsim {

namespace {

std::string context_label(const XmlStream& xs) {
  std::string label = "<" + xs.name();
  if (auto id = xs.attr("id")) label += " id=\"" + *id + "\"";
  return label + ">";
}

}  // namespace

// libxml2's SAX2 push parser, fed a chunk of the file at a time. Its callbacks queue the chunk's element
// starts and ends with their attributes; next() hands them out one by one and feeds the next chunk when the
// queue is empty. No document tree is built and attribute values are copied once, into a buffer reused
// from chunk to chunk.
struct XmlStream::Impl {
  struct Attr {
    const xmlChar* name;             // the parser's dictionary string (valid while the parser lives)
    size_t value_begin, value_size;  // in `values`
  };
  struct Queued {
    Event event;
    const xmlChar* name;
    int depth, line;
    size_t attr_begin, attr_end;  // in `attrs`
  };

  xmlParserCtxtPtr ctxt = nullptr;
  xmlParserInputBufferPtr input = nullptr;  // the file; its read callback decompresses gzip
  bool input_done = false;
  std::vector<char> chunk;
  std::vector<Queued> queue;
  size_t queue_next = 0;
  std::vector<Attr> attrs;
  std::string values;
  int depth = 0;
  size_t current_attr_begin = 0, current_attr_end = 0;  // attributes of the last event (none unless Start)
  std::pair<std::string, int> first_error;
  int entity_line = 0;   // line of the first entity reference, 0 if none
  size_t entity_at = 0;  // queue position it comes before: events up to it are handed out first

  ~Impl() {
    if (ctxt) {
      if (ctxt->myDoc) xmlFreeDoc(ctxt->myDoc);
      xmlFreeParserCtxt(ctxt);
    }
    if (input) xmlFreeParserInputBuffer(input);
  }

  int parser_line() const { return ctxt && ctxt->input ? ctxt->input->line : 0; }

  // Predefined and character references arrive decoded, except '&', which the parser (not substituting
  // entities) passes on as "&#38;"; any other '&' is a reference to a declared entity, which is refused.
  void append_value(const xmlChar* begin, const xmlChar* end) {
    const char* p = reinterpret_cast<const char*>(begin);
    const char* e = reinterpret_cast<const char*>(end);
    const char* amp = static_cast<const char*>(std::memchr(p, '&', static_cast<size_t>(e - p)));
    if (!amp) {
      values.append(p, e);
      return;
    }
    while (p < e) {
      if (*p != '&') {
        values.push_back(*p++);
      } else if (e - p >= 5 && std::memcmp(p, "&#38;", 5) == 0) {
        values.push_back('&');
        p += 5;
      } else {
        note_entity();
        values.push_back(*p++);
      }
    }
  }

  static void on_start(void* self, const xmlChar* localname, const xmlChar* prefix, const xmlChar*,
                       int nb_namespaces, const xmlChar** namespaces, int nb_attributes, int nb_defaulted,
                       const xmlChar** attributes) {
    auto* im = of(self);
    xmlParserCtxtPtr ctxt = im->ctxt;
    Queued q{Event::Start,     qualified(ctxt, prefix, localname),
             im->depth++,      im->parser_line(),
             im->attrs.size(), 0};
    // Namespace declarations first, then attributes, each in document order (as xmlTextReader lists them).
    for (int i = 0; i < nb_namespaces; ++i) {
      const xmlChar* ns_prefix = namespaces[2 * i];
      const xmlChar* uri = namespaces[2 * i + 1];
      const xmlChar* name =
          ns_prefix ? xmlDictQLookup(ctxt->dict, BAD_CAST "xmlns", ns_prefix) : BAD_CAST "xmlns";
      const size_t begin = im->values.size();
      if (uri) im->values.append(reinterpret_cast<const char*>(uri));
      im->attrs.push_back(Attr{name, begin, im->values.size() - begin});
    }
    // Defaults from a DTD's ATTLIST are not part of the element unless asked for (as libxml2's own SAX2).
    if (nb_defaulted != 0 && (ctxt->loadsubset & XML_COMPLETE_ATTRS) == 0) nb_attributes -= nb_defaulted;
    for (int i = 0; i < nb_attributes; ++i) {
      const xmlChar** a = attributes + 5 * i;  // localname, prefix, URI, value, end
      const size_t begin = im->values.size();
      im->append_value(a[3], a[4]);
      im->attrs.push_back(Attr{qualified(ctxt, a[1], a[0]), begin, im->values.size() - begin});
    }
    q.attr_end = im->attrs.size();
    im->queue.push_back(q);
  }

  static void on_end(void* self, const xmlChar* localname, const xmlChar* prefix, const xmlChar*) {
    auto* im = of(self);
    const int depth = --im->depth;
    const xmlChar* name = qualified(im->ctxt, prefix, localname);
    // An element without children ends on the line it started (as the empty element it usually is).
    int line = im->parser_line();
    if (!im->queue.empty() && im->queue.back().event == Event::Start && im->queue.back().depth == depth)
      line = im->queue.back().line;
    im->queue.push_back(Queued{Event::End, name, depth, line, 0, 0});
  }

  static void on_reference(void* self, const xmlChar*) {
    auto* im = of(self);
    im->note_entity();
  }

  void note_entity() {
    if (entity_line != 0) return;
    entity_line = parser_line();
    entity_at = queue.size();
  }

  // Keep the first error (not warnings) so the exception names the cause and the line where parsing failed.
  static void on_error(void* self, xmlErrorPtr error) {
    auto* im = of(self);
    if (!error || error->level < XML_ERR_ERROR || !im->first_error.first.empty()) return;
    std::string msg = error->message ? error->message : "malformed XML";
    while (!msg.empty() && (msg.back() == '\n' || msg.back() == ' ')) msg.pop_back();
    if (msg.empty()) msg = "malformed XML";
    // The parser reports a file cut short as "extra content"; say what it usually means.
    if (msg.find("Extra content at the end of the document") != std::string::npos)
      msg = "premature end of data or content after the root element (truncated file?)";
    im->first_error = {msg, im->parser_line()};
  }

  // libxml2's own SAX2 handlers (kept for the DTD) need the parser as their user data, so the stream's
  // state hangs off the parser's _private pointer.
  static Impl* of(void* parser) {
    return static_cast<Impl*>(static_cast<xmlParserCtxtPtr>(parser)->_private);
  }

  static const xmlChar* qualified(xmlParserCtxtPtr ctxt, const xmlChar* prefix, const xmlChar* localname) {
    return prefix ? xmlDictQLookup(ctxt->dict, prefix, localname) : localname;
  }

  // Reads the next chunk of the file into the parser; false once the whole file has been parsed.
  bool feed() {
    if (input_done) return false;
    chunk.resize(1 << 16);
    const int got = input->readcallback
                        ? input->readcallback(input->context, chunk.data(), static_cast<int>(chunk.size()))
                        : -1;
    if (got <= 0) input_done = true;  // end of file, or a read error: the parser reports what it has
    xmlParseChunk(ctxt, chunk.data(), got > 0 ? got : 0, input_done ? 1 : 0);
    return true;
  }
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
  // libxml2 decompresses gzip input transparently here.
  impl_->input = xmlParserInputBufferCreateFilename(path.c_str(), XML_CHAR_ENCODING_NONE);
  if (!impl_->input) throw InputError(SourceLoc{path, 0}, "cannot open as XML");

  // libxml2's default SAX2 handlers (they keep the internal DTD subset, so entity references are recognised
  // as such), with element events, references and errors going to this stream and text, comments and
  // processing instructions ignored.
  xmlSAXHandler sax;
  std::memset(&sax, 0, sizeof sax);
  xmlSAXVersion(&sax, 2);
  sax.startElementNs = &Impl::on_start;
  sax.endElementNs = &Impl::on_end;
  sax.reference = &Impl::on_reference;
  sax.serror = &Impl::on_error;
  sax.error = nullptr;
  sax.warning = nullptr;
  sax.fatalError = nullptr;
  sax.characters = nullptr;
  sax.ignorableWhitespace = nullptr;
  sax.cdataBlock = nullptr;
  sax.comment = nullptr;
  sax.processingInstruction = nullptr;
  impl_->ctxt = xmlCreatePushParserCtxt(&sax, nullptr, nullptr, 0, path.c_str());
  if (!impl_->ctxt) throw InputError(SourceLoc{path, 0}, "cannot open as XML");
  impl_->ctxt->_private = impl_.get();
  // No XML_PARSE_NOENT (no entity substitution), no DTDLOAD/DTDVALID, NONET: safe on untrusted input.
  // HUGE lifts libxml2's limits on text size for very large networks, not on entity expansion.
  xmlCtxtUseOptions(impl_->ctxt, XML_PARSE_NONET | XML_PARSE_HUGE | XML_PARSE_NOCDATA | XML_PARSE_BIG_LINES);
}

XmlStream::~XmlStream() = default;

XmlStream::Event XmlStream::next() {
  Impl& im = *impl_;
  for (;;) {
    if (im.entity_line != 0 && im.queue_next == im.entity_at)
      throw InputError(SourceLoc{path_, im.entity_line}, "entity references are not supported");
    if (im.queue_next < im.queue.size()) {
      const Impl::Queued& q = im.queue[im.queue_next++];
      name_.assign(reinterpret_cast<const char*>(q.name));
      depth_ = q.depth;
      line_ = q.line;
      im.current_attr_begin = q.attr_begin;
      im.current_attr_end = q.attr_end;
      return q.event;
    }
    // Everything parsed before the parser stopped has been handed out: report why it stopped.
    if (!im.first_error.first.empty() && (im.ctxt->disableSAX || im.input_done))
      throw InputError(SourceLoc{path_, im.first_error.second}, "malformed XML: " + im.first_error.first);
    im.queue.clear();
    im.queue_next = 0;
    im.attrs.clear();
    im.values.clear();
    im.current_attr_begin = im.current_attr_end = 0;
    if (!im.feed() && im.queue.empty()) {
      if (im.first_error.first.empty() && !im.ctxt->wellFormed)
        throw InputError(SourceLoc{path_, line_}, "malformed XML: malformed or truncated XML");
      return Event::Eof;
    }
  }
}

std::optional<std::string> XmlStream::attr(const char* key) const {
  const Impl& im = *impl_;
  for (size_t i = im.current_attr_begin; i < im.current_attr_end; ++i)
    if (std::strcmp(reinterpret_cast<const char*>(im.attrs[i].name), key) == 0)
      return im.values.substr(im.attrs[i].value_begin, im.attrs[i].value_size);
  return std::nullopt;
}

void XmlStream::for_each_attr_impl(void* visit,
                                   void (*call)(void*, std::string_view, std::string_view)) const {
  const Impl& im = *impl_;
  for (size_t i = im.current_attr_begin; i < im.current_attr_end; ++i)
    call(visit, reinterpret_cast<const char*>(im.attrs[i].name),
         std::string_view(im.values.data() + im.attrs[i].value_begin, im.attrs[i].value_size));
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

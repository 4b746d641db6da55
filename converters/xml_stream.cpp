#include "xml_stream.hpp"

#include <libxml/parser.h>

#include <charconv>
#include <cmath>
#include <cstring>
#include <vector>

#include "id_text.hpp"
#include "input_file.hpp"
#include "xml_parse_error.hpp"

namespace lpsim {

namespace {

std::string context_label(const XmlStream& xs) {
  std::string label = "<" + xs.name();
  if (auto id = xs.attr("id")) label += " id=\"" + *id + "\"";
  return label + ">";
}

// Attributes that hold an id or a list of ids, in any SUMO input LPSim reads (net, routes, add-files).
constexpr std::string_view kIdAttributes[] = {"id",        "type",  "route",        "from",       "to",
                                              "via",       "edges", "fromJunction", "toJunction", "fromTaz",
                                              "toTaz",     "refId", "vTypes",       "routes",     "tl",
                                              "programID", "lane",  "edge",         "incLanes",   "intLanes"};

bool is_id_attribute(std::string_view name) {
  for (std::string_view id : kIdAttributes)
    if (name == id) return true;
  return false;
}

bool has_control_character(std::string_view value) {
  for (char c : value)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) return true;
  return false;
}

// Bytes handed to the parser per xmlParseChunk call, after which the chunk's queued events are handed out.
// 64 KiB to 1 MiB parsed the load benchmark's files in the same time (within the machine's noise). Chunks
// must not be tiny: libxml2 2.9.14's push parser misreads an internal DTD subset fed a few bytes at a time
// (seen with 7-byte chunks; cut once anywhere, it is read right).
constexpr size_t kChunkSize = size_t{1} << 18;

// What libxml2 prints without a parser context to report to (an input that cannot be converted from its
// encoding) is dropped: the parse then stops with an error code, which the stream reports with file:line.
void discard_generic_error(void*, const char*, ...) {}

}  // namespace

// libxml2's SAX2 push parser (xmlCreatePushParserCtxt/xmlParseChunk), fed kChunkSize bytes of the file at
// a time from InputFile (plain or gzip). Its callbacks queue the chunk's element starts and ends, copying
// attribute values once into `values`; next() hands them out one by one and feeds the next chunk when the
// queue is empty. No document tree is built, and the file is never held whole: one chunk here, and in
// libxml2 the part it has not parsed yet (a tag cut by the chunk's end).
//
// Why SAX2 push and not xmlTextReader: the reader builds and frees a tree node for every element and
// attribute. Visiting every element and copying every attribute value through each API (libxml2 2.9.14,
// bench/make_load_scenario.py's files): routes.rou.xml (310 MB) 0.45 CPU s with the push parser against
// 0.91 s with the reader, net.xml (418 MB) 1.1 s against 2.4 s.
//
// Safety: no XML_PARSE_NOENT (entities are never substituted), no DTDLOAD/DTDVALID, NONET. The SAX handler
// has no entityDecl, getEntity or externalSubset callbacks, so a DTD's entity declarations are parsed and
// dropped and nothing is loaded: every entity reference other than the five predefined ones is an
// undeclared entity, reported as "entity references are not supported" at the reference's line, and no
// expansion can grow ("billion laughs"). That is also why XML_PARSE_HUGE, which lifts libxml2's limits on
// text and name lengths for very large networks, is safe here: the limits it also relaxes are those of
// entity expansion, which cannot happen.
struct XmlStream::Impl {
  struct Attr {
    std::string_view name;           // in libxml2's dictionary: valid as long as the parser
    size_t value_begin, value_size;  // in `values`
  };
  struct Queued {
    Event event;
    std::string_view name;  // in libxml2's dictionary
    int depth, line;
    size_t attr_begin, attr_end;  // in `attrs`
  };

  InputFile input;
  std::string path;
  xmlParserCtxtPtr ctxt = nullptr;
  std::vector<char> chunk;
  bool input_done = false;

  std::vector<Queued> queue;  // events of the chunk parsed last, handed out from queue_next on
  size_t queue_next = 0;
  std::vector<Attr> attrs;
  std::string values;
  size_t current_begin = 0, current_end = 0;  // attributes of the event handed out last (none unless Start)

  std::vector<std::string_view> open;  // names of the open elements, root first
  bool root_seen = false;
  // An end tag right after its start tag (an empty element, or one without children) is reported at the
  // start tag's line, as SUMO's parser reports it; the start tag's line is where the tag ends.
  bool last_was_start = false;
  int last_start_line = 0;

  // The first error: the events queued before it are handed out, then it is raised.
  std::optional<XmlErrorReport> error;
  size_t error_at = 0;

  explicit Impl(const std::string& p) : input(p), path(p), chunk(kChunkSize) {
    static const bool initialised = [] {
      xmlInitParser();
      return true;
    }();
    (void)initialised;
    xmlSetGenericErrorFunc(nullptr, discard_generic_error);  // per thread in libxml2
    xmlSAXHandler sax;
    std::memset(&sax, 0, sizeof sax);
    sax.initialized = XML_SAX2_MAGIC;
    sax.startDocument = &Impl::on_start_document;
    sax.startElementNs = &Impl::on_start;
    sax.endElementNs = &Impl::on_end;
    sax.serror = &Impl::on_error;
    ctxt = xmlCreatePushParserCtxt(&sax, this, nullptr, 0, p.c_str());
    if (!ctxt) throw InputError(SourceLoc{p, 0}, "cannot start the XML parser");
    xmlCtxtUseOptions(ctxt, XML_PARSE_NONET | XML_PARSE_HUGE);
  }
  ~Impl() {
    if (!ctxt) return;
    // libxml2 makes a document of its own to hold a DTD's declarations (even with no tree callbacks set),
    // which the parser context does not free.
    if (ctxt->myDoc) xmlFreeDoc(ctxt->myDoc);
    xmlFreeParserCtxt(ctxt);
  }
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;

  static Impl& of(void* self) { return *static_cast<Impl*>(self); }
  int parser_line() const { return ctxt->input ? ctxt->input->line : 0; }

  void record(XmlErrorReport report) {
    if (error) return;
    error = std::move(report);
    error_at = queue.size();
  }

  std::string_view dict_name(const xmlChar* prefix, const xmlChar* local) const {
    const xmlChar* name = prefix ? xmlDictQLookup(ctxt->dict, prefix, local) : local;
    return name ? std::string_view(reinterpret_cast<const char*>(name)) : std::string_view();
  }

  // Without entity substitution libxml2 writes each '&' of a value (from &amp; or a character reference)
  // as "&#38;" and decodes every other reference; any other '&' would be an entity reference, which the
  // parser has already refused.
  void append_value(const xmlChar* begin, const xmlChar* end) {
    const char* p = reinterpret_cast<const char*>(begin);
    const char* e = reinterpret_cast<const char*>(end);
    for (;;) {
      const char* amp = static_cast<const char*>(std::memchr(p, '&', static_cast<size_t>(e - p)));
      if (!amp) break;
      values.append(p, amp);
      values.push_back('&');
      p = (e - amp >= 5 && std::memcmp(amp, "&#38;", 5) == 0) ? amp + 5 : amp + 1;
    }
    values.append(p, e);
  }

  // Called once the XML declaration (if any) is read and the input's encoding known.
  static void on_start_document(void* self) {
    Impl& im = of(self);
    const xmlParserCtxtPtr c = im.ctxt;
    const char* declared = reinterpret_cast<const char*>(c->encoding);
    const xmlCharEncodingHandler* decoder = c->input && c->input->buf ? c->input->buf->encoder : nullptr;
    if (declared && !is_readable_encoding(declared))
      im.record({unsupported_encoding_message(declared, true), im.parser_line()});
    else if (decoder && decoder->name && !is_readable_encoding(decoder->name))
      im.record({unsupported_encoding_message(decoder->name, false), im.parser_line()});
  }

  static void on_start(void* self, const xmlChar* localname, const xmlChar* prefix, const xmlChar*,
                       int nb_namespaces, const xmlChar** namespaces, int nb_attributes, int nb_defaulted,
                       const xmlChar** attributes) {
    Impl& im = of(self);
    if (im.error) return;
    const int line = im.parser_line();  // where the start tag ends: the callback comes before its '>'
    Queued q{Event::Start,
             im.dict_name(prefix, localname),
             static_cast<int>(im.open.size()),
             line,
             im.attrs.size(),
             0};
    // Namespace declarations first, then the attributes, each in document order.
    for (int i = 0; i < nb_namespaces; ++i) {
      const xmlChar* ns_prefix = namespaces[2 * i];
      const xmlChar* uri = namespaces[2 * i + 1];
      const std::string_view name = ns_prefix ? im.dict_name(BAD_CAST "xmlns", ns_prefix) : "xmlns";
      const size_t begin = im.values.size();
      if (uri) im.values.append(reinterpret_cast<const char*>(uri));
      im.attrs.push_back(Attr{name, begin, im.values.size() - begin});
    }
    // The defaulted attributes (from a DTD's ATTLIST, listed last) are not in the document.
    const int written = nb_attributes - nb_defaulted;
    for (int i = 0; i < written; ++i) {
      const xmlChar** a = attributes + 5 * i;  // localname, prefix, URI, value begin, value end
      const size_t begin = im.values.size();
      im.append_value(a[3], a[4]);
      im.attrs.push_back(Attr{im.dict_name(a[1], a[0]), begin, im.values.size() - begin});
    }
    q.attr_end = im.attrs.size();
    im.check_ids(q, line);
    im.queue.push_back(q);
    im.open.push_back(q.name);
    im.root_seen = true;
    im.last_was_start = true;
    im.last_start_line = line;
  }

  // Ids with control characters break the outputs' XML and the one-line messages (converters/id_text.hpp).
  // Literal tabs and newlines in a value are spaces by then (XML's attribute normalisation): only character
  // references put control characters there, so one scan of a value without one is all it costs. Recorded
  // before the element is queued: it is never handed out.
  void check_ids(const Queued& q, int line) {
    for (size_t i = q.attr_begin; i < q.attr_end; ++i) {
      const std::string_view v = value(attrs[i]);
      if (!has_control_character(v) || !is_id_attribute(attrs[i].name)) continue;
      // Appended piecewise: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string temporaries.
      std::string message = "<";
      message += q.name;
      for (size_t k = q.attr_begin; k < q.attr_end; ++k)
        if (attrs[k].name == "id") {
          message += " id=\"";
          message += printable(value(attrs[k]));
          message += '"';
        }
      message += ">: attribute '";
      message += attrs[i].name;
      message += "' ";
      message += id_problem(v);
      message += ": '";
      message += printable(v);
      message += "'";
      record({std::move(message), line});
      return;
    }
  }

  static void on_end(void* self, const xmlChar*, const xmlChar*, const xmlChar*) {
    Impl& im = of(self);
    if (im.error || im.open.empty()) return;
    const int line = im.last_was_start ? im.last_start_line : im.parser_line();
    im.last_was_start = false;
    const std::string_view name = im.open.back();
    im.open.pop_back();
    const size_t none = im.attrs.size();
    im.queue.push_back(Queued{Event::End, name, static_cast<int>(im.open.size()), line, none, none});
  }

  static void on_error(void* self, xmlErrorPtr e) {
    Impl& im = of(self);
    if (im.error || !e) return;
    // LPSim reads no namespaces: an undeclared prefix is part of a name, as in XML 1.0 without them.
    if (e->domain == XML_FROM_NAMESPACE) return;
    if (e->level < XML_ERR_ERROR && e->code != XML_WAR_UNDECLARED_ENTITY) return;
    // A tag cut by the end of the input is still reported as a start before the error: take it back, so
    // that no element is handed out with its attributes missing.
    if (e->code == XML_ERR_GT_REQUIRED && !im.queue.empty() && im.queue.back().event == Event::Start &&
        e->str1 && im.queue.back().name == reinterpret_cast<const char*>(e->str1)) {
      im.attrs.resize(im.queue.back().attr_begin);
      im.queue.pop_back();
      im.open.pop_back();
    }
    const XmlErrorScene scene{im.open.empty() ? std::string_view() : im.open.back(), im.root_seen,
                              im.input_done};
    im.record(describe_xml_error(*e, *im.ctxt, scene));
  }

  // Reads the next chunk of the file into the parser (the last call tells it the input ended).
  void feed() {
    const size_t got = input.read(chunk.data(), chunk.size());
    input_done = got == 0;
    const int status = xmlParseChunk(ctxt, chunk.data(), static_cast<int>(got), input_done ? 1 : 0);
    if (status != 0 && !error)
      record({"malformed XML: libxml2 stopped with status " + std::to_string(status), parser_line()});
  }

  std::string_view value(const Attr& a) const {
    return std::string_view(values.data() + a.value_begin, a.value_size);
  }
};

XmlStream::XmlStream(const std::string& path) : impl_(std::make_unique<Impl>(path)), path_(path) {}

XmlStream::~XmlStream() = default;

XmlStream::Event XmlStream::next() {
  Impl& im = *impl_;
  for (;;) {
    if (im.queue_next < im.queue.size() && !(im.error && im.queue_next == im.error_at)) {
      const Impl::Queued& q = im.queue[im.queue_next++];
      name_.assign(q.name);
      depth_ = q.depth;
      line_ = q.line;
      im.current_begin = q.attr_begin;
      im.current_end = q.attr_end;
      return q.event;
    }
    im.current_begin = im.current_end = 0;
    if (im.error) throw InputError(SourceLoc{path_, im.error->line}, im.error->message);
    if (im.input_done) {
      // libxml2 reports an unfinished document; this only guards against it staying silent.
      if (!im.open.empty() || !im.root_seen)
        throw InputError(SourceLoc{path_, im.parser_line()}, "malformed XML: premature end of data");
      return Event::Eof;
    }
    im.queue.clear();
    im.queue_next = 0;
    im.attrs.clear();
    im.values.clear();
    im.feed();
  }
}

std::optional<std::string> XmlStream::attr(const char* key) const {
  const Impl& im = *impl_;
  const std::string_view k(key);
  for (size_t i = im.current_begin; i < im.current_end; ++i)
    if (im.attrs[i].name == k) return std::string(im.value(im.attrs[i]));
  return std::nullopt;
}

void XmlStream::for_each_attr_impl(void* visit,
                                   void (*call)(void*, std::string_view, std::string_view)) const {
  const Impl& im = *impl_;
  for (size_t i = im.current_begin; i < im.current_end; ++i)
    call(visit, im.attrs[i].name, im.value(im.attrs[i]));
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

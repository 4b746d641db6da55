#pragma once
// LPSim's words for what libxml2 reports on bad input. libxml2's own messages name parser functions
// ("xmlParseEntityRef: no name") or say "Extra content at the end of the document" for a file cut short;
// users and tests get one line that says what is wrong in the file, and the line where it is.
#include <libxml/parser.h>

#include <string>
#include <string_view>

namespace lpsim {

/// What the stream knows about the document beyond the error itself.
struct XmlErrorScene {
  std::string_view open_element;  // innermost element still open, "" when none
  bool root_seen = false;         // a root element has started
  bool at_end = false;            // the parser had been told the input ended
};

struct XmlErrorReport {
  std::string message;  // complete, one line
  int line = 0;
};

/// The report for libxml2's error `e`, raised while `ctxt` parsed.
XmlErrorReport describe_xml_error(const xmlError& e, const xmlParserCtxt& ctxt, const XmlErrorScene& scene);

/// LPSim reads UTF-8 and ISO-8859-1 (and ASCII, a subset of both), by any of their usual names.
bool is_readable_encoding(std::string_view name);

/// "unsupported encoding ..." for a declared ('quoted') or a detected encoding.
std::string unsupported_encoding_message(std::string_view name, bool declared);

}  // namespace lpsim

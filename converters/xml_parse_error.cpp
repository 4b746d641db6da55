#include "xml_parse_error.hpp"

#include <algorithm>
#include <array>
#include <cstring>

namespace lpsim {

namespace {

bool iequals(std::string_view a, std::string_view b) {
  return a.size() == b.size() &&
         std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) { return (x | 0x20) == (y | 0x20); });
}

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

std::string_view text(const char* s) { return s ? std::string_view(s) : std::string_view(); }

// libxml2's message on one line, without its trailing line break.
std::string one_line(const char* message) {
  std::string out = message ? message : "";
  std::replace(out.begin(), out.end(), '\n', ' ');
  while (!out.empty() && out.back() == ' ') out.pop_back();
  return out.empty() ? std::string("malformed or truncated XML") : out;
}

// The start tag the parser stopped in, read back from its input buffer: libxml2 names neither the element
// nor the attribute for some attribute errors. `cur` is where the parser stopped, inside the tag; the
// tag's '<' is the last one before it, as none may stand in the well-formed attributes before `cur`.
struct TagAtError {
  std::string_view element, attribute;  // empty when not found
};

TagAtError tag_at(const xmlParserInput* input) {
  TagAtError tag;
  if (!input || !input->base || !input->cur || !input->end || input->cur >= input->end) return tag;
  const char* base = reinterpret_cast<const char*>(input->base);
  const char* cur = reinterpret_cast<const char*>(input->cur);
  const char* end = reinterpret_cast<const char*>(input->end);
  const char* lt = cur;
  while (lt > base && *(lt - 1) != '<') --lt;
  if (lt == base) return tag;
  auto name_at = [end](const char*& p) {
    const char* from = p;
    while (p < end && !is_space(*p) && *p != '=' && *p != '/' && *p != '>' && *p != '<') ++p;
    return std::string_view(from, static_cast<size_t>(p - from));
  };
  auto skip_space = [end](const char*& p) {
    while (p < end && is_space(*p)) ++p;
  };
  const char* p = lt;
  tag.element = name_at(p);
  for (;;) {
    skip_space(p);
    if (p >= cur) return tag;
    const std::string_view name = name_at(p);
    if (name.empty()) return tag;
    skip_space(p);
    if (p >= end || *p != '=' || p >= cur) {
      tag.attribute = name;
      return tag;
    }
    ++p;
    skip_space(p);
    if (p >= cur || (*p != '"' && *p != '\'')) {
      tag.attribute = name;
      return tag;
    }
    const void* close = std::memchr(p + 1, *p, static_cast<size_t>(end - p - 1));
    if (!close || static_cast<const char*>(close) >= cur) {
      tag.attribute = name;
      return tag;
    }
    p = static_cast<const char*>(close) + 1;
  }
}

// The line of the end of the input the parser holds: a file cut short is reported where it ends.
int line_at_end(const xmlParserCtxt& ctxt) {
  const xmlParserInput* in = ctxt.input;
  if (!in || !in->cur || !in->end) return in ? in->line : 0;
  return in->line + static_cast<int>(std::count(in->cur, in->end, '\n'));
}

std::string malformed(const std::string& what) { return "malformed XML: " + what; }

std::string attribute_error(const xmlParserCtxt& ctxt, const std::string& before, const std::string& after,
                            const char* fallback) {
  const TagAtError tag = tag_at(ctxt.input);
  if (tag.attribute.empty()) return malformed(fallback);
  return malformed(before + std::string(tag.attribute) + after);
}

}  // namespace

XmlErrorReport describe_xml_error(const xmlError& e, const xmlParserCtxt& ctxt, const XmlErrorScene& scene) {
  XmlErrorReport r{"", e.line};
  const std::string_view message = text(e.message);
  switch (e.code) {
    case XML_ERR_UNDECLARED_ENTITY:
    case XML_WAR_UNDECLARED_ENTITY:
    case XML_ERR_UNPARSED_ENTITY:
    case XML_ERR_ENTITY_PE_INTERNAL:
    case XML_ERR_ENTITY_BOUNDARY:
      // Entity declarations are never stored (XmlStream's SAX handler has no entityDecl), so every
      // reference other than the predefined five lands here.
      r.message = "entity references are not supported";
      break;
    case XML_ERR_UNSUPPORTED_ENCODING:
    case XML_ERR_UNKNOWN_ENCODING:
      r.message = unsupported_encoding_message(e.str1 ? text(e.str1) : "?", true);
      break;
    case XML_ERR_DOCUMENT_EMPTY:
      r.message = malformed("no root element");
      break;
    case XML_ERR_DOCUMENT_END:
      // libxml2 says "Extra content at the end of the document" both for content after the root element
      // and for a document that ends too early.
      if (!scene.open_element.empty()) {
        r.message =
            malformed("premature end of data in <" + std::string(scene.open_element) + "> (truncated file?)");
        r.line = line_at_end(ctxt);
      } else if (!scene.root_seen) {
        r.message = malformed("no root element");
      } else {
        r.message = malformed("premature end of data or content after the root element (truncated file?)");
      }
      break;
    case XML_ERR_TAG_NAME_MISMATCH:
      r.message = malformed("opening and ending tag mismatch: " + std::string(text(e.str1)) + " and " +
                            std::string(text(e.str2)));
      break;
    case XML_ERR_GT_REQUIRED:
      r.message = malformed(one_line(e.message) + (scene.at_end ? " (truncated file?)" : ""));
      break;
    case XML_ERR_ATTRIBUTE_WITHOUT_VALUE:
      r.message = malformed("attribute " + std::string(text(e.str1)) + " without a value");
      break;
    case XML_ERR_ATTRIBUTE_NOT_STARTED:
      r.message = attribute_error(ctxt, "attribute ", " not quoted", "attribute value not quoted");
      break;
    case XML_ERR_LT_IN_ATTRIBUTE:
      r.message = attribute_error(ctxt, "'<' in the value of attribute ", "", "'<' in an attribute value");
      break;
    case XML_ERR_SPACE_REQUIRED:
    case XML_ERR_NAME_REQUIRED:
      if (message.find("EntityRef") != std::string_view::npos) {
        r.message = malformed("'&' not followed by a reference (write &amp;)");
      } else if (message.find("attribute") != std::string_view::npos) {
        const TagAtError tag = tag_at(ctxt.input);
        r.message =
            malformed(tag.element.empty() ? std::string("bad attribute syntax")
                                          : "bad attribute syntax in <" + std::string(tag.element) + ">");
      } else {
        r.message = malformed(one_line(e.message));
      }
      break;
    case XML_ERR_ENTITYREF_SEMICOL_MISSING:
      r.message = malformed("'&' not followed by a reference (write &amp;)");
      break;
    case XML_ERR_INVALID_HEX_CHARREF:
    case XML_ERR_INVALID_DEC_CHARREF:
    case XML_ERR_INVALID_CHARREF:
      r.message = malformed("invalid character reference");
      break;
    case XML_ERR_INVALID_CHAR:
      // The same code stands for a reference to a character XML does not allow and for bytes that are not
      // the document's encoding.
      r.message = message.find("CharRef") != std::string_view::npos
                      ? malformed("invalid character reference (code point " + std::to_string(e.int1) + ")")
                      : malformed(one_line(e.message));
      break;
    case XML_ERR_RESERVED_XML_NAME:
      // Also raised for processing instructions named like "XmL", which libxml2 words its own way.
      r.message = message.find("XML declaration") != std::string_view::npos
                      ? malformed("XML declaration not at the start of the file")
                      : malformed(one_line(e.message));
      break;
    default:
      r.message = malformed(one_line(e.message));
      break;
  }
  return r;
}

bool is_readable_encoding(std::string_view name) {
  static constexpr std::array<std::string_view, 8> kNames{"UTF-8",      "UTF8",       "US-ASCII", "ASCII",
                                                          "ISO-8859-1", "ISO_8859-1", "LATIN1",   "LATIN-1"};
  return std::any_of(kNames.begin(), kNames.end(), [name](std::string_view n) { return iequals(n, name); });
}

std::string unsupported_encoding_message(std::string_view name, bool declared) {
  std::string message = "unsupported encoding ";
  if (declared) message += '\'';
  message += name;
  if (declared) message += '\'';
  return message + " (LPSim reads UTF-8 and ISO-8859-1)";
}

}  // namespace lpsim

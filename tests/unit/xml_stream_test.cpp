#include "converters/xml_stream.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include "converters/output_file.hpp"
#include "core/error.hpp"
#include "temp_dir.hpp"

namespace lpsim {
namespace {

class XmlStreamTest : public ::testing::Test {
 protected:
  std::string write(const std::string& name, const std::string& text) const { return tmp_.write(name, text); }

  // Message of the InputError raised while reading the whole file (empty if none).
  static std::string error_reading(const std::string& path) {
    try {
      XmlStream xs(path);
      while (xs.next() != XmlStream::Event::Eof) {
      }
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }

  test::TempDir tmp_{"lpsim_xml"};
};

// A file of several parser chunks (256 KiB each): every element arrives in order with its depth, and an empty
// element's End comes right after its Start, on its line.
TEST_F(XmlStreamTest, EventsDepthsAndLinesAcrossChunks) {
  std::string text = "<?xml version=\"1.0\"?>\n<root>\n";
  const int n = 20000;
  for (int i = 0; i < n; ++i)
    text += "  <item id=\"i" + std::to_string(i) + "\"><leaf v=\"" + std::to_string(i) + "\"/></item>\n";
  text += "</root>\n";
  ASSERT_GT(text.size(), 4u * 65536u);
  XmlStream xs(write("many.xml", text));
  int items = 0, leaves = 0, ends = 0;
  for (;;) {
    auto ev = xs.next();
    if (ev == XmlStream::Event::Eof) break;
    if (ev == XmlStream::Event::End) {
      ++ends;
      continue;
    }
    if (xs.name() == "item") {
      EXPECT_EQ(xs.depth(), 1);
      EXPECT_EQ(xs.line(), 3 + items);
      EXPECT_EQ(xs.required("id"), "i" + std::to_string(items));
      ++items;
    } else if (xs.name() == "leaf") {
      EXPECT_EQ(xs.depth(), 2);
      EXPECT_EQ(xs.integer("v", -1), leaves);
      const int line = xs.line();
      ASSERT_EQ(xs.next(), XmlStream::Event::End);
      ++ends;
      EXPECT_EQ(xs.name(), "leaf");
      EXPECT_EQ(xs.depth(), 2);
      EXPECT_EQ(xs.line(), line);
      EXPECT_FALSE(xs.has("v"));  // attributes belong to Start events only
      ++leaves;
    }
  }
  EXPECT_EQ(items, n);
  EXPECT_EQ(leaves, n);
  EXPECT_EQ(ends, 2 * n + 1);
}

// Lines stay exact past 65535 (libxml2 stores tree-node lines in 16 bits).
TEST_F(XmlStreamTest, LinesAreExactBeyond65535) {
  std::string text = "<root>\n";
  for (int i = 0; i < 70000; ++i) text += "<a/>\n";
  text += "<b id=\"late\"/>\n</root>\n";
  XmlStream xs(write("long.xml", text));
  int b_line = 0;
  for (auto ev = xs.next(); ev != XmlStream::Event::Eof; ev = xs.next())
    if (ev == XmlStream::Event::Start && xs.name() == "b") b_line = xs.line();
  EXPECT_EQ(b_line, 70002);
}

TEST_F(XmlStreamTest, PredefinedAndCharacterReferencesAreDecoded) {
  XmlStream xs(write("refs.xml", "<r v=\"a&amp;b&#38;c&lt;&#x41;&quot;\" w=\"&apos;\"/>"));
  ASSERT_EQ(xs.next(), XmlStream::Event::Start);
  EXPECT_EQ(xs.get("v", ""), "a&b&c<A\"");
  EXPECT_EQ(xs.get("w", ""), "'");
  std::vector<std::pair<std::string, std::string>> seen;
  xs.for_each_attr([&](std::string_view n, std::string_view v) { seen.emplace_back(n, v); });
  ASSERT_EQ(seen.size(), 2u);
  EXPECT_EQ(seen[0].second, "a&b&c<A\"");
}

// for_each_attr lists namespace declarations first, then attributes by their qualified names, in document
// order; attr() finds only unprefixed attributes by name.
TEST_F(XmlStreamTest, NamespaceDeclarationsAndPrefixedAttributes) {
  XmlStream xs(write("ns.xml", "<r xmlns:xsi=\"urn:x\" xsi:k=\"1\" k=\"2\"/>"));
  ASSERT_EQ(xs.next(), XmlStream::Event::Start);
  std::vector<std::pair<std::string, std::string>> seen;
  xs.for_each_attr([&](std::string_view n, std::string_view v) { seen.emplace_back(n, v); });
  const std::vector<std::pair<std::string, std::string>> expected{
      {"xmlns:xsi", "urn:x"}, {"xsi:k", "1"}, {"k", "2"}};
  EXPECT_EQ(seen, expected);
  EXPECT_EQ(xs.get("k", ""), "2");
}

TEST_F(XmlStreamTest, EntityReferencesAreRefusedInContentAndAttributes) {
  const std::string dtd = "<?xml version=\"1.0\"?>\n<!DOCTYPE r [<!ENTITY e \"expanded\">]>\n";
  std::string in_content = error_reading(write("content.xml", dtd + "<r>\n<a/>\n&e;\n</r>\n"));
  EXPECT_NE(in_content.find("content.xml:5: entity references are not supported"), std::string::npos)
      << in_content;
  std::string in_attr = error_reading(write("attr.xml", dtd + "<r>\n<a id=\"&e;\"/>\n</r>\n"));
  EXPECT_NE(in_attr.find("attr.xml:4: entity references are not supported"), std::string::npos) << in_attr;
  // Elements before the reference are still handed out.
  XmlStream xs(write("before.xml", dtd + "<r>\n<a/>\n<b v=\"&e;\"/>\n</r>\n"));
  EXPECT_EQ(xs.next(), XmlStream::Event::Start);  // r
  EXPECT_EQ(xs.next(), XmlStream::Event::Start);  // a
  EXPECT_EQ(xs.name(), "a");
  EXPECT_EQ(xs.next(), XmlStream::Event::End);
  EXPECT_THROW(xs.next(), InputError);
}

// Entity declarations are dropped, never expanded nor loaded: nested ones ("billion laughs") and external
// ones (general or parameter) end in the same refusal, at the line of the first reference.
TEST_F(XmlStreamTest, DeclaredEntitiesAreNeitherExpandedNorLoaded) {
  std::string laughs = "<?xml version=\"1.0\"?>\n<!DOCTYPE r [\n<!ENTITY l0 \"lol\">\n";
  for (int i = 1; i <= 9; ++i) {
    laughs += "<!ENTITY l" + std::to_string(i) + " \"";
    for (int k = 0; k < 10; ++k) laughs += "&l" + std::to_string(i - 1) + ";";
    laughs += "\">\n";
  }
  laughs += "]>\n<r>\n<a v=\"&l9;\"/>\n&l9;\n</r>\n";
  const std::string in_laughs = error_reading(write("laughs.xml", laughs));
  EXPECT_NE(in_laughs.find("laughs.xml:15: entity references are not supported"), std::string::npos)
      << in_laughs;
  const std::string external = error_reading(write(
      "external.xml", "<!DOCTYPE r [\n<!ENTITY x SYSTEM \"file:///etc/hostname\">\n]>\n<r>\n&x;\n</r>\n"));
  EXPECT_NE(external.find("external.xml:5: entity references are not supported"), std::string::npos)
      << external;
  const std::string parameter = error_reading(write(
      "parameter.xml", "<!DOCTYPE r [\n<!ENTITY % p SYSTEM \"file:///etc/hostname\">\n%p;\n]>\n<r/>\n"));
  EXPECT_NE(parameter.find("parameter.xml:3: entity references are not supported"), std::string::npos)
      << parameter;
}

// A start tag cut by the end of the file is not handed out (with the attributes read so far): the error
// comes right after the last complete element.
TEST_F(XmlStreamTest, StartTagCutByTheEndOfTheFileIsNotHandedOut) {
  XmlStream xs(write("cut.xml", "<r>\n<a v=\"1\"/>\n<b w=\"2\" x"));
  EXPECT_EQ(xs.next(), XmlStream::Event::Start);
  EXPECT_EQ(xs.next(), XmlStream::Event::Start);
  EXPECT_EQ(xs.name(), "a");
  EXPECT_EQ(xs.next(), XmlStream::Event::End);
  try {
    xs.next();
    ADD_FAILURE() << "no error; last element " << xs.name();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("cut.xml:3: malformed XML"), std::string::npos) << e.what();
  }
}

TEST_F(XmlStreamTest, MalformedXmlNamesTheLineWhereParsingStopped) {
  std::string text = "<root>\n";
  for (int i = 0; i < 5000; ++i) text += "  <a x=\"1\"/>\n";
  text += "  <a x=\"1\" x=\"2\"/>\n</root>\n";
  std::string msg = error_reading(write("bad.xml", text));
  EXPECT_NE(msg.find("bad.xml:5002: malformed XML: Attribute x redefined"), std::string::npos) << msg;
  std::string cut = error_reading(write("cut.xml", "<root>\n  <a/>\n  <b"));
  EXPECT_NE(cut.find("malformed XML"), std::string::npos) << cut;
}

// Comments, processing instructions, CDATA, text and a DOCTYPE whose internal subset holds '>' and ']' in
// quoted literals and comments are skipped; the elements around them arrive with their lines.
TEST_F(XmlStreamTest, MarkupOtherThanElementsIsSkipped) {
  const std::string text =
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      "<!DOCTYPE r [<!ATTLIST a v CDATA \"x>]y\"> <!-- ]> -->]>\n"
      "<!-- <fake/> -->\n"
      "<r>\n"
      "  <?pi <no/> ?>\n"
      "  text &amp; &#x3C;refs&gt; <![CDATA[ <not an=\"element\"/> ]]>\n"
      "  <a v='say \"hi\"'/><b\n"
      "     w = \"2\" ></b>\n"
      "</r>\n"
      "<!-- trailing comment -->\n";
  XmlStream xs(write("markup.xml", text));
  std::vector<std::string> seen;
  for (auto ev = xs.next(); ev != XmlStream::Event::Eof; ev = xs.next())
    seen.push_back((ev == XmlStream::Event::Start ? "+" : "-") + xs.name() + "@" + std::to_string(xs.line()) +
                   (ev == XmlStream::Event::Start ? xs.get("v", "") + xs.get("w", "") : ""));
  const std::vector<std::string> expected{"+r@4",
                                          "+a@7say \"hi\"",
                                          "-a@7",
                                          "+b@8"
                                          "2",
                                          "-b@8",
                                          "-r@9"};
  EXPECT_EQ(seen, expected);
}

// Tabs and line breaks in attribute values read as spaces (CR LF as one), as XML's normalisation has it.
TEST_F(XmlStreamTest, AttributeValuesAreNormalised) {
  XmlStream xs(write("norm.xml", "<r v=\"a\nb\tc\r\nd\" w=\"&#10;\"/>"));
  ASSERT_EQ(xs.next(), XmlStream::Event::Start);
  EXPECT_EQ(xs.get("v", ""), "a b c d");
  EXPECT_EQ(xs.get("w", ""), "\n");  // a character reference is kept as written
}

TEST_F(XmlStreamTest, EncodingsUtf8WithBomAndLatin1AreRead) {
  XmlStream bom(write("bom.xml",
                      "\xEF\xBB\xBF<?xml version=\"1.0\"?>\n<r v=\"Stra\xC3\x9F"
                      "e\"/>"));
  ASSERT_EQ(bom.next(), XmlStream::Event::Start);
  EXPECT_EQ(bom.get("v", ""),
            "Stra\xC3\x9F"
            "e");
  XmlStream latin1(write("latin1.xml",
                         "<?xml version=\"1.0\" encoding=\"ISO-8859-1\"?>\n<r v=\"Stra\xDF"
                         "e\"/>"));
  ASSERT_EQ(latin1.next(), XmlStream::Event::Start);
  EXPECT_EQ(latin1.get("v", ""),
            "Stra\xC3\x9F"
            "e");
  const std::string utf16 = error_reading(write("utf16.xml", std::string("\xFF\xFE<\0r\0/\0>\0", 10)));
  EXPECT_NE(utf16.find("utf16.xml:1: unsupported encoding UTF-16"), std::string::npos) << utf16;
  const std::string sjis =
      error_reading(write("sjis.xml", "<?xml version=\"1.0\" encoding=\"Shift_JIS\"?>\n<r/>"));
  EXPECT_NE(sjis.find("unsupported encoding 'Shift_JIS'"), std::string::npos) << sjis;
}

// Each structural error is caught and named with its line; nothing is guessed.
TEST_F(XmlStreamTest, StructuralErrorsNameTheirLine) {
  auto error = [&](const std::string& text) { return error_reading(write("e.xml", text)); };
  EXPECT_NE(
      error("<r>\n<a>\n</b>\n</r>").find("e.xml:3: malformed XML: opening and ending tag mismatch: a and b"),
      std::string::npos);
  EXPECT_NE(
      error("<r/>\n<r/>").find("e.xml:2: malformed XML: premature end of data or content after the root"),
      std::string::npos);
  EXPECT_NE(error("<r/>\ntext").find("e.xml:2: malformed XML"), std::string::npos);
  EXPECT_NE(error("<r>\n<a v=1/>\n</r>").find("e.xml:2: malformed XML: attribute v not quoted"),
            std::string::npos);
  EXPECT_NE(error("<r>\n<a v/>\n</r>").find("e.xml:2: malformed XML: attribute v without a value"),
            std::string::npos);
  EXPECT_NE(error("<r>\n<a v=\"<\"/>\n</r>").find("e.xml:2: malformed XML: '<' in the value of attribute v"),
            std::string::npos);
  EXPECT_NE(error("<r>\n<a v=\"1\"w=\"2\"/>\n</r>").find("e.xml:2: malformed XML: bad attribute syntax"),
            std::string::npos);
  EXPECT_NE(error("<r>\n<a v=\"&#0;\"/>\n</r>").find("e.xml:2: malformed XML: invalid character reference"),
            std::string::npos);
  EXPECT_NE(error("<r>\n a & b\n</r>").find("e.xml:2: malformed XML: '&' not followed by a reference"),
            std::string::npos);
  EXPECT_NE(error("<r>\n<a>\n").find("e.xml:3: malformed XML: premature end of data in <a>"),
            std::string::npos);
  EXPECT_NE(error("<!-- only a comment -->\n").find("malformed XML: no root element"), std::string::npos);
  // A declaration anywhere but at the very start is refused, even after the buffer has been refilled.
  EXPECT_NE(error(" <?xml version=\"1.0\"?><r/>").find("XML declaration not at the start"),
            std::string::npos);
  EXPECT_NE(error("<r>\n" + std::string(300000, ' ') + "<?xml version=\"1.0\" encoding=\"ISO-8859-1\"?></r>")
                .find("e.xml:2: malformed XML: XML declaration not at the start"),
            std::string::npos);
}

// A start tag longer than the read buffer (an attribute of 1 MB) is read whole.
TEST_F(XmlStreamTest, TagsLongerThanTheBufferAreReadWhole) {
  const std::string big(1 << 20, 'e');
  XmlStream xs(write("big.xml", "<r>\n<a v=\"" + big + "\" w=\"1\"/>\n<b/>\n</r>\n"));
  ASSERT_EQ(xs.next(), XmlStream::Event::Start);
  ASSERT_EQ(xs.next(), XmlStream::Event::Start);
  EXPECT_EQ(xs.get("v", "").size(), big.size());
  EXPECT_EQ(xs.get("w", ""), "1");
  EXPECT_EQ(xs.line(), 2);
  ASSERT_EQ(xs.next(), XmlStream::Event::End);
  ASSERT_EQ(xs.next(), XmlStream::Event::Start);
  EXPECT_EQ(xs.name(), "b");
  EXPECT_EQ(xs.line(), 3);
}

TEST_F(XmlStreamTest, GzipFilesReadLikePlainOnes) {
  std::string text = "<root>\n";
  for (int i = 0; i < 3000; ++i) text += "  <a id=\"" + std::to_string(i) + "\"/>\n";
  text += "</root>\n";
  const std::string gz = (tmp_.path() / "f.xml.gz").string();
  {
    OutputFile out(gz);
    out.text(text);
    out.close();
  }
  auto ids = [](const std::string& path) {
    long long sum = 0;
    int count = 0;
    XmlStream xs(path);
    for (auto ev = xs.next(); ev != XmlStream::Event::Eof; ev = xs.next())
      if (ev == XmlStream::Event::Start && xs.name() == "a") {
        sum += xs.integer("id", 0);
        ++count;
      }
    return std::make_pair(count, sum);
  };
  EXPECT_EQ(ids(gz), ids(write("f.xml", text)));
  EXPECT_EQ(ids(gz).first, 3000);
  // A gzip file cut short is an error, not a shorter document.
  std::string bytes;
  {
    std::ifstream in(gz, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  const std::string cut = error_reading(write("cut.xml.gz", bytes.substr(0, bytes.size() / 2)));
  EXPECT_NE(cut.find("cut.xml.gz"), std::string::npos) << cut;
}

}  // namespace
}  // namespace lpsim

#include "converters/xml_stream.hpp"

#include <gtest/gtest.h>

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

// A file of several parser chunks (64 KiB each): every element arrives in order with its depth, and an empty
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

TEST_F(XmlStreamTest, MalformedXmlNamesTheLineWhereParsingStopped) {
  std::string text = "<root>\n";
  for (int i = 0; i < 5000; ++i) text += "  <a x=\"1\"/>\n";
  text += "  <a x=\"1\" x=\"2\"/>\n</root>\n";
  std::string msg = error_reading(write("bad.xml", text));
  EXPECT_NE(msg.find("bad.xml:5002: malformed XML: Attribute x redefined"), std::string::npos) << msg;
  std::string cut = error_reading(write("cut.xml", "<root>\n  <a/>\n  <b"));
  EXPECT_NE(cut.find("malformed XML"), std::string::npos) << cut;
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
}

}  // namespace
}  // namespace lpsim

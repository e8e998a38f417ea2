#include "relief/core/xml_writer.h"

#include <limits>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

namespace relief {
namespace {

std::string escaped(std::string_view text, XmlEscaping rules = {}) {
  std::string out;
  append_xml_escaped(out, text, rules);
  return out;
}

TEST(XmlEscape, MarkupCharactersBecomeEntities) {
  EXPECT_EQ(escaped(R"(a & b < c > d "e")"), "a &amp; b &lt; c &gt; d &quot;e&quot;");
  EXPECT_EQ(escaped("O'Farrell"), "O'Farrell");
  EXPECT_EQ(escaped("O'Farrell", {.apostrophe = true}), "O&#39;Farrell");
}

TEST(XmlEscape, WhitespaceIsRawInTextAndReferencedInAttributes) {
  EXPECT_EQ(escaped("a\tb\nc\rd"), "a\tb\nc\rd");
  EXPECT_EQ(escaped("a\tb\nc\rd", {.whitespace_as_references = true}), "a&#9;b&#10;c&#13;d");
}

TEST(XmlEscape, WhatXmlCannotCarryBecomesReplacementCharacter) {
  // C0 controls other than TAB/LF/CR, a stray continuation byte, a truncated sequence, an
  // overlong lead byte: each byte becomes U+FFFD; valid UTF-8 passes whole.
  EXPECT_EQ(escaped("a\x01z"), "a\xEF\xBF\xBDz");
  EXPECT_EQ(escaped(std::string_view("\0", 1)), "\xEF\xBF\xBD");
  EXPECT_EQ(escaped("\x80"), "\xEF\xBF\xBD");
  EXPECT_EQ(escaped("\xE2\x82"), "\xEF\xBF\xBD\xEF\xBF\xBD");
  EXPECT_EQ(escaped("\xC0\xAF"), "\xEF\xBF\xBD\xEF\xBF\xBD");
  EXPECT_EQ(escaped("Stra\xC3\x9F"
                    "e \xE2\x82\xAC \xF0\x9F\x9A\x97"),
            "Stra\xC3\x9F"
            "e \xE2\x82\xAC \xF0\x9F\x9A\x97");
}

TEST(XmlWriter, NestsIndentsAndClosesEmptyElementsShort) {
  std::string out;
  XmlWriter xml(out, {.indent = 2});
  xml.declaration();
  xml.start("a");
  xml.start("b");
  xml.attribute("k", "v");
  xml.end("b");
  xml.start("c");
  xml.start("d");
  xml.end("d");
  xml.end("c");
  xml.comment("note");
  xml.end("a");
  xml.finish();
  EXPECT_EQ(out,
            "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
            "<a>\n"
            "  <b k=\"v\"/>\n"
            "  <c>\n"
            "    <d/>\n"
            "  </c>\n"
            "  <!-- note -->\n"
            "</a>\n");
}

TEST(XmlWriter, IndentWidthIsAnOption) {
  std::string out;
  XmlWriter xml(out, {.indent = 4});
  xml.start("a");
  xml.start("b");
  xml.end("b");
  xml.end("a");
  EXPECT_EQ(out, "<a>\n    <b/>\n</a>\n");
}

TEST(XmlWriter, AttributesAreEscapedWithTheirWhitespaceKept) {
  std::string out;
  XmlWriter xml(out);
  xml.start("tag");
  xml.attribute("v", "1 < 2 & \"x\"\nO'Farrell");
  xml.end("tag");
  EXPECT_EQ(out, "<tag v=\"1 &lt; 2 &amp; &quot;x&quot;&#10;O'Farrell\"/>\n");

  std::string html;
  XmlWriter apostrophes(html, {.indent = 2, .escape_apostrophe = true});
  apostrophes.start("tag");
  apostrophes.attribute("v", "O'Farrell");
  apostrophes.text("it's");
  apostrophes.end("tag");
  EXPECT_EQ(html, "<tag v=\"O&#39;Farrell\">it&#39;s</tag>\n");
}

TEST(XmlWriter, NumbersPrintAsTheNumberFormatDoes) {
  std::string out;
  XmlWriter xml(out);
  xml.start("n");
  xml.attribute_int("i", -42);
  xml.attribute_fixed("f", 1.23456, 3);
  xml.attribute_fixed("z", -0.0001, 3);  // rounds to zero: no sign
  xml.attribute_fixed("w", 7.6, 0);
  xml.attribute_shortest("s", 0.0001525);
  xml.attribute_shortest("e", -2.5e-9);
  xml.attribute_shortest("m", -0.0);
  xml.end("n");
  EXPECT_EQ(out, "<n i=\"-42\" f=\"1.235\" z=\"0.000\" w=\"8\" s=\"0.0001525\" e=\"-2.5e-09\" m=\"0\"/>\n");
}

TEST(XmlWriter, TextAndCdataStayOnTheElementsLine) {
  std::string out;
  XmlWriter xml(out);
  xml.start("root");
  xml.start("t");
  xml.text("a < b\n");
  xml.end("t");
  xml.start("geo");
  xml.cdata("+proj=a ]]> b");
  xml.end("geo");
  xml.end("root");
  EXPECT_EQ(out,
            "<root>\n"
            "  <t>a &lt; b\n</t>\n"
            "  <geo><![CDATA[+proj=a ]]]]><![CDATA[> b]]></geo>\n"
            "</root>\n");
}

TEST(XmlWriter, MisuseFailsLoudly) {
  std::string out;
  {
    XmlWriter xml(out);
    xml.start("a");
    xml.start("b");
    EXPECT_THROW(xml.end("a"), std::logic_error);  // <b> is the innermost open element
  }
  {
    XmlWriter xml(out);
    EXPECT_THROW(xml.end("a"), std::logic_error);  // nothing open
  }
  {
    XmlWriter xml(out);
    xml.start("a");
    xml.start("b");
    xml.end("b");
    EXPECT_THROW(xml.attribute("k", "v"), std::logic_error);  // <a>'s start tag is closed
  }
  {
    XmlWriter xml(out);
    xml.start("a");
    EXPECT_THROW(xml.finish(), std::logic_error);  // <a> left open
    xml.end("a");
    EXPECT_NO_THROW(xml.finish());
    EXPECT_THROW(xml.start("b"), std::logic_error);  // a second root
    EXPECT_THROW(xml.declaration(), std::logic_error);
  }
  {
    XmlWriter xml(out);
    xml.start("a");
    xml.text("t");
    EXPECT_THROW(xml.start("b"), std::logic_error);  // mixed content
    EXPECT_THROW(xml.comment("c"), std::logic_error);
  }
  {
    XmlWriter xml(out);
    EXPECT_THROW(xml.start("a b"), std::logic_error);
    EXPECT_THROW(xml.start(""), std::logic_error);
    xml.start("a");
    EXPECT_THROW(xml.attribute("x=\"1\" y", "v"), std::logic_error);
    EXPECT_THROW(xml.comment("a -- b"), std::logic_error);
    EXPECT_THROW(xml.comment("ends-"), std::logic_error);
  }
  {
    XmlWriter xml(out);
    EXPECT_THROW(xml.finish(), std::logic_error);  // no root
  }
}

}  // namespace
}  // namespace relief

#pragma once
// The one XML emitter of relief: a streaming writer (no document tree) that appends indented
// elements, attributes, text, CDATA and comments to a string, and the one escaper it uses, which
// the HTML report shares. Written by hand rather than with pugixml so that numbers come out
// exactly as the outputs print them (number_format.h) and a large network needs no DOM.

#include <string>
#include <string_view>
#include <vector>

namespace relief {

/// How `append_xml_escaped` writes text. Always: & < > " become &amp; &lt; &gt; &quot;, and what
/// XML 1.0 cannot carry (control characters other than TAB, LF and CR, bytes that are not
/// UTF-8) becomes U+FFFD, so that the document always parses.
struct XmlEscaping {
  /// TAB, LF and CR as &#9; &#10; &#13;. An attribute value keeps them only so: a parser turns
  /// raw ones into spaces (XML 1.0 section 3.3.3). Text keeps them raw.
  bool whitespace_as_references = false;
  /// ' as &#39; (needed inside a single-quoted attribute, as HTML may have; SUMO's plain XML has
  /// always been written so).
  bool apostrophe = false;
};

/// Appends `text` escaped by `rules`.
void append_xml_escaped(std::string& out, std::string_view text, XmlEscaping rules = {});

/// Writes one XML document into `out`, element by element:
///
///     XmlWriter xml(out, {.indent = 2});
///     xml.declaration();
///     xml.start("road");
///     xml.attribute("name", name);          // escaped
///     xml.attribute_fixed("length", 12.5, 3);
///     xml.end("road");                      // <road name="..." length="12.500"/>
///     xml.finish();
///
/// Each element starts on its own line, indented by its depth; an element without children is
/// closed with "/>", one with text or CDATA stays on one line. Misuse (an attribute after the
/// start tag is closed, closing an element that is not the innermost open one, content after
/// text, an element left open at finish, "--" in a comment) throws std::logic_error: it is a bug
/// in the caller, not a defect of the data.
class XmlWriter {
 public:
  struct Options {
    int indent = 2;  ///< spaces per level of nesting
    /// ' as &#39; in attributes and text (see XmlEscaping::apostrophe).
    bool escape_apostrophe = false;
  };

  explicit XmlWriter(std::string& out) : XmlWriter(out, Options{}) {}
  XmlWriter(std::string& out, Options options) : out_(out), options_(options) {}

  /// `<?xml version="1.0" encoding="UTF-8"?>` and a line break; only before the root element.
  void declaration();
  /// `<!-- text -->` on its own line at the current depth.
  void comment(std::string_view text);

  /// Opens element `name`; attributes may follow until its first child, text or end.
  void start(std::string_view name);
  /// An attribute of the element just started, its value escaped.
  void attribute(std::string_view name, std::string_view value);
  /// An integer attribute.
  void attribute_int(std::string_view name, long long value);
  /// A number with exactly `decimals` digits after the point (append_fixed: no "-0.000").
  void attribute_fixed(std::string_view name, double value, int decimals);
  /// The shortest text that reads back as exactly `value` (append_shortest).
  void attribute_shortest(std::string_view name, double value);

  /// Text content of the element just started, escaped; its end tag follows on the same line.
  void text(std::string_view text);
  /// `<![CDATA[text]]>` as the content of the element just started ("]]>" in `text` is split
  /// across two sections).
  void cdata(std::string_view text);

  /// Closes `name`, which must be the innermost open element.
  void end(std::string_view name);
  /// Checks that every element has been closed.
  void finish() const;

  /// Number of open elements.
  [[nodiscard]] std::size_t depth() const { return open_.size(); }

 private:
  void close_start_tag(bool line_break);
  void indent(std::size_t depth);
  void begin_attribute(std::string_view name);
  void begin_content(const char* what, std::string_view name);

  std::string& out_;
  Options options_;
  std::vector<std::string> open_;  // names of the open elements, innermost last
  bool in_start_tag_ = false;      // "<name attr=..." written, ">" not yet
  bool has_text_ = false;          // the innermost element holds text or CDATA
  bool has_root_ = false;
};

}  // namespace relief

#include "relief/core/xml_writer.h"

#include <stdexcept>

#include "relief/core/number_format.h"

namespace relief {
namespace {

constexpr std::string_view kReplacement = "\xEF\xBF\xBD";  // U+FFFD in UTF-8

// Length of the UTF-8 sequence at p[0..n) when it is well formed (no overlong two-byte form,
// nothing above U+10FFFF by its lead byte), else 0.
std::size_t utf8_length(const unsigned char* p, std::size_t n) {
  const unsigned char c = p[0];
  const std::size_t len = (c & 0xE0) == 0xC0 ? 2 : (c & 0xF0) == 0xE0 ? 3 : (c & 0xF8) == 0xF0 ? 4 : 0;
  if (len == 0 || len > n || c < 0xC2 || c > 0xF4) return 0;
  for (std::size_t k = 1; k < len; ++k) {
    if ((p[k] & 0xC0) != 0x80) return 0;
  }
  return len;
}

// Element and attribute names: letters, digits and _ : . - (the ASCII part of XML 1.0's Name).
bool valid_name(std::string_view name) {
  if (name.empty()) return false;
  for (const char c : name) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
                    c == ':' || c == '.' || c == '-';
    if (!ok) return false;
  }
  return true;
}

[[noreturn]] void misuse(const std::string& what) {
  throw std::logic_error("XmlWriter: " + what);
}

}  // namespace

void append_xml_escaped(std::string& out, std::string_view text, XmlEscaping rules) {
  const auto* p = reinterpret_cast<const unsigned char*>(text.data());
  const std::size_t n = text.size();
  for (std::size_t i = 0; i < n;) {
    const unsigned char c = p[i];
    if (c >= 0x80) {
      // Multi-byte UTF-8 is copied whole; a broken sequence loses one byte to U+FFFD.
      const std::size_t len = utf8_length(p + i, n - i);
      if (len == 0) {
        out += kReplacement;
        ++i;
      } else {
        out.append(text.substr(i, len));
        i += len;
      }
      continue;
    }
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += rules.apostrophe ? "&#39;" : "'";
        break;
      case '\t':
        out += rules.whitespace_as_references ? "&#9;" : "\t";
        break;
      case '\n':
        out += rules.whitespace_as_references ? "&#10;" : "\n";
        break;
      case '\r':
        out += rules.whitespace_as_references ? "&#13;" : "\r";
        break;
      default:
        if (c < 0x20) {
          out += kReplacement;  // XML 1.0 forbids the other C0 controls
        } else {
          out += static_cast<char>(c);
        }
    }
    ++i;
  }
}

void XmlWriter::declaration() {
  if (has_root_) misuse("the declaration must come before the root element");
  out_ += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
}

void XmlWriter::comment(std::string_view text) {
  if (text.find("--") != std::string_view::npos || (!text.empty() && text.back() == '-'))
    misuse("a comment may not contain \"--\" or end with '-'");
  begin_content("a comment", {});
  indent(open_.size());
  out_ += "<!-- ";
  out_ += text;
  out_ += " -->\n";
}

void XmlWriter::start(std::string_view name) {
  if (!valid_name(name)) misuse("'" + std::string(name) + "' is not an element name");
  if (open_.empty() && has_root_) misuse("a second root element <" + std::string(name) + ">");
  begin_content("element", name);
  indent(open_.size());
  out_ += '<';
  out_ += name;
  open_.emplace_back(name);
  in_start_tag_ = true;
  has_root_ = true;
}

void XmlWriter::attribute(std::string_view name, std::string_view value) {
  begin_attribute(name);
  append_xml_escaped(out_, value,
                     {.whitespace_as_references = true, .apostrophe = options_.escape_apostrophe});
  out_ += '"';
}

void XmlWriter::attribute_int(std::string_view name, long long value) {
  begin_attribute(name);
  append_int(out_, value);
  out_ += '"';
}

void XmlWriter::attribute_fixed(std::string_view name, double value, int decimals) {
  begin_attribute(name);
  append_fixed(out_, value, decimals);
  out_ += '"';
}

void XmlWriter::attribute_shortest(std::string_view name, double value) {
  begin_attribute(name);
  append_shortest(out_, value);
  out_ += '"';
}

void XmlWriter::text(std::string_view text) {
  if (!in_start_tag_ && !has_text_) misuse("text must follow the start of its element directly");
  close_start_tag(false);
  append_xml_escaped(out_, text,
                     {.whitespace_as_references = false, .apostrophe = options_.escape_apostrophe});
  has_text_ = true;
}

void XmlWriter::cdata(std::string_view text) {
  if (!in_start_tag_ && !has_text_) misuse("CDATA must follow the start of its element directly");
  close_start_tag(false);
  out_ += "<![CDATA[";
  // "]]>" would end the section: end it after "]]" and start the next with ">".
  for (std::size_t at = text.find("]]>"); at != std::string_view::npos; at = text.find("]]>")) {
    out_ += text.substr(0, at + 2);
    out_ += "]]><![CDATA[";
    text.remove_prefix(at + 2);
  }
  out_ += text;
  out_ += "]]>";
  has_text_ = true;
}

void XmlWriter::end(std::string_view name) {
  if (open_.empty()) misuse("</" + std::string(name) + "> closes no open element");
  if (open_.back() != name)
    misuse("</" + std::string(name) + "> closes <" + open_.back() + ">, which is still open");
  if (in_start_tag_) {
    out_ += "/>\n";
    in_start_tag_ = false;
  } else {
    if (!has_text_) indent(open_.size() - 1);
    out_ += "</";
    out_ += name;
    out_ += ">\n";
  }
  open_.pop_back();
  has_text_ = false;
}

void XmlWriter::finish() const {
  if (!open_.empty()) misuse("<" + open_.back() + "> is still open at the end of the document");
  if (!has_root_) misuse("the document has no root element");
}

void XmlWriter::close_start_tag(bool line_break) {
  if (!in_start_tag_) return;
  out_ += line_break ? ">\n" : ">";
  in_start_tag_ = false;
}

void XmlWriter::indent(std::size_t depth) {
  out_.append(depth * static_cast<std::size_t>(options_.indent), ' ');
}

void XmlWriter::begin_attribute(std::string_view name) {
  if (!in_start_tag_) misuse("attribute '" + std::string(name) + "' after its element's start tag");
  if (!valid_name(name)) misuse("'" + std::string(name) + "' is not an attribute name");
  out_ += ' ';
  out_ += name;
  out_ += "=\"";
}

// Before a child element or comment: the parent's start tag ends its line; no text before it.
void XmlWriter::begin_content(const char* what, std::string_view name) {
  if (has_text_) {
    misuse(std::string(what) + (name.empty() ? "" : " <" + std::string(name) + ">") +
           " after text (mixed content is not supported)");
  }
  close_start_tag(true);
}

}  // namespace relief

#include "export/html_text.h"

#include "relief/core/number_format.h"
#include "relief/core/xml_writer.h"

namespace relief::html {

void append_escaped(std::string& out, std::string_view text) {
  // Text and attribute values alike: ' too (attributes may be single-quoted), whitespace raw.
  append_xml_escaped(out, text, {.whitespace_as_references = false, .apostrophe = true});
}

std::string esc(std::string_view text) {
  std::string out;
  append_escaped(out, text);
  return out;
}

std::string fixed(double value, int decimals) {
  std::string out;
  append_fixed(out, value, decimals);
  return out;
}

std::string integer(std::size_t value) {
  std::string out;
  append_int(out, static_cast<long long>(value));
  return out;
}

}  // namespace relief::html

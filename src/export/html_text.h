#pragma once
// Text for the HTML report: escaping that keeps the page valid XML, and fixed-point numbers.

#include <cstddef>
#include <string>
#include <string_view>

namespace relief::html {

/// Appends `text` escaped for HTML and XML alike (core/xml_writer.h's escaper with ' as &#39;):
/// bytes that are not valid UTF-8 and control characters XML 1.0 forbids become U+FFFD, so
/// that the page always parses.
void append_escaped(std::string& out, std::string_view text);
/// `text` escaped (see append_escaped).
[[nodiscard]] std::string esc(std::string_view text);
/// `value` with exactly `decimals` digits after the point, locale-independent.
[[nodiscard]] std::string fixed(double value, int decimals);
/// `value` in decimal.
[[nodiscard]] std::string integer(std::size_t value);

}  // namespace relief::html

#pragma once
// Base64 (RFC 4648, with padding) of raw bytes: the 3D view's typed arrays travel inside
// <script> files (a browser loads those from file://, where fetch() of a binary file is
// refused), report.html's picture inside a data: URL.

#include <string>
#include <string_view>

namespace relief::detail {

/// Appends the base64 text of `bytes` to `out`.
void append_base64(std::string& out, std::string_view bytes);

}  // namespace relief::detail

#include "relief/core/number_format.h"

#include <array>
#include <charconv>
#include <cmath>

namespace relief {

void append_fixed(std::string& out, double value, int decimals) {
  // Values that round to zero print without a sign.
  if (std::abs(value) < 0.5 * std::pow(10.0, -decimals)) value = 0.0;
  std::array<char, 64> buf{};
  const auto res =
      std::to_chars(buf.data(), buf.data() + buf.size(), value, std::chars_format::fixed, decimals);
  out.append(buf.data(), res.ptr);
}

void append_shortest(std::string& out, double value) {
  if (value == 0.0) value = 0.0;  // no "-0"
  std::array<char, 64> buf{};
  const auto res = std::to_chars(buf.data(), buf.data() + buf.size(), value);
  out.append(buf.data(), res.ptr);
}

void append_int(std::string& out, long long value) {
  std::array<char, 24> buf{};
  const auto res = std::to_chars(buf.data(), buf.data() + buf.size(), value);
  out.append(buf.data(), res.ptr);
}

}  // namespace relief

#include "relief/core/number_format.h"

#include <gtest/gtest.h>

namespace relief {
namespace {

TEST(NumberFormat, FixedDecimals) {
  std::string s;
  append_fixed(s, -122.4039123456, 7);
  s += ' ';
  append_fixed(s, 12.3456, 3);
  s += ' ';
  append_fixed(s, -0.0001, 3);
  s += ' ';
  append_fixed(s, 2.5, 0);
  s += ' ';
  append_int(s, -42);
  EXPECT_EQ(s, "-122.4039123 12.346 0.000 2 -42");
  std::string t;
  append_shortest(t, 9.15e-07);
  t += ' ';
  append_shortest(t, -0.0);
  t += ' ';
  append_shortest(t, 0.1 + 0.2);
  EXPECT_EQ(t, "9.15e-07 0 0.30000000000000004");
}

}  // namespace
}  // namespace relief

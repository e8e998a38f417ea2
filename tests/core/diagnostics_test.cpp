#include "relief/core/diagnostics.h"

#include <gtest/gtest.h>

namespace relief {
namespace {

TEST(Diagnostics, CountsEveryReportButKeepsOnlyTheFirstPerCode) {
  Diagnostics d(2);
  int heard = 0;
  d.set_listener([&](const Diagnostic&) { ++heard; });
  for (int i = 0; i < 5; ++i) d.report(Severity::warning, "osm.missing_node", "node " + std::to_string(i));
  d.report(Severity::error, "elevation.void", "void");
  EXPECT_EQ(d.total(), 6u);
  EXPECT_EQ(d.count("osm.missing_node"), 5u);
  EXPECT_EQ(d.count("elevation.void"), 1u);
  EXPECT_EQ(d.count("unknown"), 0u);
  EXPECT_EQ(d.kept().size(), 3u);
  EXPECT_EQ(d.kept()[1].message, "node 1");
  EXPECT_EQ(heard, 6);
}

TEST(Diagnostics, SeverityNames) {
  EXPECT_EQ(to_string(Severity::info), "info");
  EXPECT_EQ(to_string(Severity::warning), "warning");
  EXPECT_EQ(to_string(Severity::error), "error");
}

}  // namespace
}  // namespace relief

#pragma once
// Paths of test data: the real San Francisco data in ../shared/data (beside the project root)
// and a per-test scratch directory. Tests that need shared data skip when it is absent.

#include <filesystem>
#include <string>

namespace testing {
class TestInfo;
}

namespace relief::test {

/// ../shared/data/<relative> next to the source tree (or $RELIEF_SHARED_DATA/<relative>).
[[nodiscard]] std::filesystem::path shared_data(const std::string& relative);
/// True when the shared data folder exists.
[[nodiscard]] bool have_shared_data();
/// <source>/fixtures/<relative>.
[[nodiscard]] std::filesystem::path fixture(const std::string& relative);
/// A fresh empty directory for the current test (removed and recreated on each call), under a
/// folder named for the running test (<tmp>/<Suite.Test>/<name>), so tests running side by side
/// never share one.
[[nodiscard]] std::filesystem::path scratch_dir(const std::string& name);
/// True when RELIEF_KEEP_TEST_OUTPUT is set (not empty, not 0): tests keep what they write.
[[nodiscard]] bool keep_test_output();
/// The folder that holds a test's scratch directories (<tmp>/<Suite.Test>); the test main removes
/// it when the test passes, unless RELIEF_KEEP_TEST_OUTPUT=1.
[[nodiscard]] std::filesystem::path test_scratch_root(const ::testing::TestInfo& info);

}  // namespace relief::test

/// Skips the current test when ../shared/data is not present.
#define RELIEF_REQUIRE_SHARED_DATA()                                              \
  do {                                                                            \
    if (!::relief::test::have_shared_data()) GTEST_SKIP() << "no ../shared/data"; \
  } while (0)

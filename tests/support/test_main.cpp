// The test executables' main: GoogleTest's, plus removing the scratch folder of every test that
// passed. The suite writes whole builds of real regions (about 6 GB per build tree at 2e34337);
// left behind, two build trees in CI filled the disk. A failed test keeps its folder to look at,
// and RELIEF_KEEP_TEST_OUTPUT=1 keeps them all.

#include <gtest/gtest.h>

#include <filesystem>
#include <system_error>

#include "support/test_data.h"

namespace {

class RemoveScratchOfPassedTests : public ::testing::EmptyTestEventListener {
  void OnTestEnd(const ::testing::TestInfo& info) override {
    if (!info.result()->Passed()) return;
    std::error_code ignored;  // a folder that cannot be removed costs disk, not a test
    std::filesystem::remove_all(relief::test::test_scratch_root(info), ignored);
  }
};

}  // namespace

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  if (!relief::test::keep_test_output()) {
    ::testing::UnitTest::GetInstance()->listeners().Append(new RemoveScratchOfPassedTests);
  }
  return RUN_ALL_TESTS();
}

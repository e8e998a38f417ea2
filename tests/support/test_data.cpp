#include "support/test_data.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>
#include <string_view>

namespace relief::test {

std::filesystem::path shared_data(const std::string& relative) {
  if (const char* env = std::getenv("RELIEF_SHARED_DATA")) return std::filesystem::path(env) / relative;
  return std::filesystem::path(RELIEF_SOURCE_DIR).parent_path() / "shared" / "data" / relative;
}

bool have_shared_data() {
  return std::filesystem::is_directory(shared_data(""));
}

std::filesystem::path fixture(const std::string& relative) {
  return std::filesystem::path(RELIEF_SOURCE_DIR) / "fixtures" / relative;
}

bool keep_test_output() {
  const char* keep = std::getenv("RELIEF_KEEP_TEST_OUTPUT");
  return keep != nullptr && std::string_view(keep) != "" && std::string_view(keep) != "0";
}

std::filesystem::path test_scratch_root(const ::testing::TestInfo& info) {
  return std::filesystem::path(RELIEF_TEST_TMP_DIR) /
         (std::string(info.test_suite_name()) + "." + info.name());
}

std::filesystem::path scratch_dir(const std::string& name) {
  // Under the running test's own folder: ctest runs the tests of one binary side by side, and
  // helpers shared by several tests ask for the same name.
  const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::filesystem::path dir = info != nullptr ? test_scratch_root(*info) : RELIEF_TEST_TMP_DIR;
  dir /= name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace relief::test

#include "support/test_data.h"

#include <cstdlib>

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

std::filesystem::path scratch_dir(const std::string& name) {
  const auto dir = std::filesystem::path(RELIEF_TEST_TMP_DIR) / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace relief::test

#include "relief/core/atomic_file.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "relief/core/errors.h"
#include "support/test_data.h"

namespace relief {
namespace {

std::string read_all(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::size_t count_files(const std::filesystem::path& dir) {
  return static_cast<std::size_t>(std::distance(std::filesystem::directory_iterator(dir), {}));
}

TEST(AtomicFile, WritesContentAndLeavesNoTemporary) {
  const auto dir = test::scratch_dir("atomic_ok");
  write_file_atomically(dir / "a.txt", "hello\n");
  EXPECT_EQ(read_all(dir / "a.txt"), "hello\n");
  EXPECT_EQ(count_files(dir), 1u);
}

TEST(AtomicFile, FailingWriterKeepsOldFileAndRemovesTemporary) {
  const auto dir = test::scratch_dir("atomic_fail");
  write_file_atomically(dir / "a.txt", "old");
  EXPECT_THROW(write_file_atomically(dir / "a.txt",
                                     [](std::ostream& out) {
                                       out << "half";
                                       throw InvalidInput("stop");
                                     }),
               InvalidInput);
  EXPECT_EQ(read_all(dir / "a.txt"), "old");
  EXPECT_EQ(count_files(dir), 1u);
}

TEST(AtomicFile, UnwritableDirectoryThrowsIoError) {
  EXPECT_THROW(write_file_atomically("/nonexistent-dir/x/a.txt", "x"), IoError);
}

TEST(OutputSet, NothingAppearsUntilCommit) {
  const auto dir = test::scratch_dir("output_set");
  {
    OutputSet set;
    set.add(dir / "a.txt", [](std::ostream& out) { out << "a"; });
    set.add(dir / "b.txt", [](std::ostream& out) { out << "b"; });
    EXPECT_FALSE(std::filesystem::exists(dir / "a.txt"));
    // Destroyed without commit: temporaries vanish.
  }
  EXPECT_EQ(count_files(dir), 0u);
  OutputSet set;
  set.add(dir / "a.txt", [](std::ostream& out) { out << "a"; });
  set.commit();
  EXPECT_EQ(read_all(dir / "a.txt"), "a");
  EXPECT_EQ(count_files(dir), 1u);
}

}  // namespace
}  // namespace relief

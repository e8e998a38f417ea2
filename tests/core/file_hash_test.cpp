// SHA-256 of bytes and files: the standard's test vectors, and a GDAL virtual path hashed by the
// file it reads from.
#include <gtest/gtest.h>

#include <fstream>

#include "relief/core/errors.h"
#include "relief/core/file_hash.h"
#include "support/test_data.h"

namespace relief {
namespace {

TEST(FileHash, Sha256OfTheStandardsVectors) {
  EXPECT_EQ(sha256_hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(sha256_hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
}

TEST(FileHash, AFileAndAGdalVirtualPathIntoIt) {
  const std::filesystem::path dir = test::scratch_dir("hash");
  const std::filesystem::path file = dir / "a.zip";
  {
    std::ofstream out(file, std::ios::binary);
    for (int i = 0; i < 100000; ++i) out << "abc";  // several read blocks
  }
  std::string bytes;
  for (int i = 0; i < 100000; ++i) bytes += "abc";
  const std::string expected = sha256_hex(bytes);
  EXPECT_EQ(sha256_of_file(file), expected);
  EXPECT_EQ(sha256_of_file("/vsizip/" + file.string() + "/inner/b.hgt"), expected);  // "/vsizip//abs/..."
  EXPECT_EQ(sha256_of_file("/vsigzip/" + file.string()), expected);
  EXPECT_THROW((void)sha256_of_file(dir / "missing.tif"), IoError);
  EXPECT_THROW((void)sha256_of_file("/vsizip/" + (dir / "missing.zip").string() + "/b.hgt"), IoError);
}

// A plan records its inputs so that any working directory reads the same files.
TEST(FileHash, AnInputPathReadsTheSameFileFromAnyWorkingDirectory) {
  const std::filesystem::path dir = test::scratch_dir("input_paths");
  std::ofstream(dir / "dem.zip") << "zip";
  std::ofstream(dir / "dem.tif") << "tif";
  const std::filesystem::path before = std::filesystem::current_path();
  std::filesystem::current_path(dir.parent_path());
  const std::string name = dir.filename().string();
  const std::string abs = dir.lexically_normal().string();
  EXPECT_EQ(absolute_input_path(name + "/dem.tif"), abs + "/dem.tif");
  EXPECT_EQ(absolute_input_path("./" + name + "/dem.tif"), abs + "/dem.tif");
  EXPECT_EQ(absolute_input_path("/vsizip/" + name + "/dem.zip/inner/b.hgt"),
            "/vsizip/" + abs + "/dem.zip/inner/b.hgt");
  EXPECT_EQ(absolute_input_path("/vsigzip/" + name + "/dem.zip"), "/vsigzip/" + abs + "/dem.zip");
  // As given: absolute, not found, a container already absolute, a URL.
  EXPECT_EQ(absolute_input_path(abs + "/dem.tif"), abs + "/dem.tif");
  EXPECT_EQ(absolute_input_path(name + "/missing.tif"), name + "/missing.tif");
  EXPECT_EQ(absolute_input_path("/vsizip/" + abs + "/dem.zip/b.hgt"), "/vsizip/" + abs + "/dem.zip/b.hgt");
  EXPECT_EQ(absolute_input_path("/vsizip/" + name + "/missing.zip/b.hgt"),
            "/vsizip/" + name + "/missing.zip/b.hgt");
  EXPECT_EQ(absolute_input_path("/vsicurl/https://example.org/dem.tif"),
            "/vsicurl/https://example.org/dem.tif");
  std::filesystem::current_path(before);
}

}  // namespace
}  // namespace relief

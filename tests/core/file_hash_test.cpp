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

}  // namespace
}  // namespace relief

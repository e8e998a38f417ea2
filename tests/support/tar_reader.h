#pragma once
// Reading a .tar.gz back in tests (the CARLA package): gzip by zlib, then POSIX ustar with every
// header's magic and checksum checked (gtest failures where they differ).

#include <map>
#include <string>
#include <vector>

namespace relief::test {

/// One entry of a tar archive.
struct TarEntry {
  std::string path;  ///< prefix + "/" + name when the prefix field is set
  char type = 0;     ///< '0' file, '5' directory
  unsigned mode = 0;
  long long mtime = 0;
  std::string bytes;
};

/// The bytes of a single-member gzip stream (a test failure when it is not one).
[[nodiscard]] std::string gunzip(const std::string& packed);

/// The entries of a ustar archive in order: each header's magic "ustar\0" "00" and checksum,
/// the end of two zero blocks and a size of whole 10240-byte records are checked.
[[nodiscard]] std::vector<TarEntry> read_tar(const std::string& tar);

/// The entries of a .tar.gz by path.
[[nodiscard]] std::map<std::string, TarEntry> read_tar_gz(const std::string& packed);

}  // namespace relief::test

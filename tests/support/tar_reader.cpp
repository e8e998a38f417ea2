#include "support/tar_reader.h"

#include <gtest/gtest.h>
#include <zlib.h>

#include <algorithm>
#include <cstring>

namespace relief::test {
namespace {

long long octal(const char* field, std::size_t width) {
  long long v = 0;
  for (std::size_t i = 0; i < width && field[i] >= '0' && field[i] <= '7'; ++i) v = 8 * v + (field[i] - '0');
  return v;
}

bool zeros(const char* begin, const char* end) {
  return std::all_of(begin, end, [](char c) { return c == '\0'; });
}

}  // namespace

std::string gunzip(const std::string& packed) {
  z_stream z{};
  EXPECT_EQ(inflateInit2(&z, 16 + MAX_WBITS), Z_OK);  // the gzip wrapper only
  std::string out;
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(packed.data()));
  z.avail_in = static_cast<uInt>(packed.size());
  std::vector<char> buffer(1 << 16);
  int rc = Z_OK;
  while (rc == Z_OK) {
    z.next_out = reinterpret_cast<Bytef*>(buffer.data());
    z.avail_out = static_cast<uInt>(buffer.size());
    rc = inflate(&z, Z_NO_FLUSH);
    out.append(buffer.data(), buffer.size() - z.avail_out);
  }
  EXPECT_EQ(rc, Z_STREAM_END);
  EXPECT_EQ(z.avail_in, 0u) << "bytes after the gzip member";
  inflateEnd(&z);
  return out;
}

std::vector<TarEntry> read_tar(const std::string& tar) {
  std::vector<TarEntry> entries;
  EXPECT_EQ(tar.size() % 10240, 0u);
  std::size_t at = 0;
  while (at + 512 <= tar.size()) {
    const char* h = tar.data() + at;
    if (zeros(h, h + 512)) {
      EXPECT_GE(tar.size() - at, 1024u) << "one zero block only";
      EXPECT_TRUE(zeros(h, tar.data() + tar.size()));
      return entries;
    }
    EXPECT_EQ(std::string(h + 257, 6), std::string("ustar\0", 6));
    EXPECT_EQ(std::string(h + 263, 2), "00");
    unsigned sum = 0;
    for (int i = 0; i < 512; ++i) sum += (i >= 148 && i < 156) ? ' ' : static_cast<unsigned char>(h[i]);
    EXPECT_EQ(octal(h + 148, 8), sum) << "checksum of entry " << entries.size();
    TarEntry e;
    const std::string name(h, strnlen(h, 100));
    const std::string prefix(h + 345, strnlen(h + 345, 155));
    e.path = prefix.empty() ? name : prefix + "/" + name;
    e.type = h[156];
    e.mode = static_cast<unsigned>(octal(h + 100, 8));
    e.mtime = octal(h + 136, 12);
    const auto size = static_cast<std::size_t>(octal(h + 124, 12));
    at += 512;
    EXPECT_LE(at + size, tar.size());
    e.bytes = tar.substr(at, size);
    at += (size + 511) / 512 * 512;
    entries.push_back(std::move(e));
  }
  ADD_FAILURE() << "no end-of-archive blocks";
  return entries;
}

std::map<std::string, TarEntry> read_tar_gz(const std::string& packed) {
  std::map<std::string, TarEntry> m;
  for (TarEntry& e : read_tar(gunzip(packed))) m[e.path] = std::move(e);
  return m;
}

}  // namespace relief::test

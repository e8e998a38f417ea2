#include "export/fbx_binary_writer.h"

#include <gtest/gtest.h>
#include <zlib.h>

#include <cstring>
#include <limits>

#include "relief/core/errors.h"

namespace relief::fbx {
namespace {

constexpr std::size_t kHeaderBytes = 27;  // magic (23) + version (4)

template <typename T>
T read_at(const std::string& b, std::size_t at) {
  T v{};
  std::memcpy(&v, b.data() + at, sizeof v);
  return v;
}

EncodeOptions uncompressed() {
  EncodeOptions o;
  o.compress_min_bytes = std::numeric_limits<std::size_t>::max();
  return o;
}

TEST(FbxBinaryWriter, WritesHeaderRecordAndEveryScalarPropertyType) {
  const Node n{"N",
               {std::int16_t{-2}, true, std::int32_t{7}, 1.5f, 2.25, std::int64_t{-9}, std::string("ab"),
                Raw{std::string("\0\1", 2)}},
               {}};
  const std::string b = encode_binary({n}, uncompressed());
  EXPECT_EQ(b.substr(0, 23), std::string("Kaydara FBX Binary  \0\x1a\0", 23));
  EXPECT_EQ(read_at<std::uint32_t>(b, 23), 7400u);
  // Properties: Y 1+2, C 1+1, I 1+4, F 1+4, D 1+8, L 1+8, S 1+4+2, R 1+4+2 = 47 bytes.
  const std::size_t record = kHeaderBytes;
  const std::size_t end = record + 13 + 1 + 47;  // no children, has properties: no null record
  EXPECT_EQ(read_at<std::uint32_t>(b, record), end);
  EXPECT_EQ(read_at<std::uint32_t>(b, record + 4), 8u);
  EXPECT_EQ(read_at<std::uint32_t>(b, record + 8), 47u);
  EXPECT_EQ(b[record + 12], 1);
  EXPECT_EQ(b[record + 13], 'N');
  std::size_t at = record + 14;
  EXPECT_EQ(b[at], 'Y');
  EXPECT_EQ(read_at<std::int16_t>(b, at + 1), -2);
  at += 3;
  EXPECT_EQ(b[at], 'C');
  EXPECT_EQ(b[at + 1], 1);
  at += 2;
  EXPECT_EQ(b[at], 'I');
  EXPECT_EQ(read_at<std::int32_t>(b, at + 1), 7);
  at += 5;
  EXPECT_EQ(b[at], 'F');
  EXPECT_EQ(read_at<float>(b, at + 1), 1.5f);
  at += 5;
  EXPECT_EQ(b[at], 'D');
  EXPECT_EQ(read_at<double>(b, at + 1), 2.25);
  at += 9;
  EXPECT_EQ(b[at], 'L');
  EXPECT_EQ(read_at<std::int64_t>(b, at + 1), -9);
  at += 9;
  EXPECT_EQ(b[at], 'S');
  EXPECT_EQ(read_at<std::uint32_t>(b, at + 1), 2u);
  EXPECT_EQ(b.substr(at + 5, 2), "ab");
  at += 7;
  EXPECT_EQ(b[at], 'R');
  EXPECT_EQ(b.substr(at + 5, 2), std::string("\0\1", 2));
  at += 7;
  EXPECT_EQ(at, end);
  // Then the top-level null record and the footer (id, padding, version, 120 zeros, magic).
  EXPECT_EQ(b.substr(end, 13), std::string(13, '\0'));
  EXPECT_EQ(static_cast<unsigned char>(b[end + 13]), 0xfa);
  EXPECT_EQ((b.size() - 140) % 16, 0u);
  EXPECT_EQ(read_at<std::uint32_t>(b, b.size() - 140), 7400u);
}

TEST(FbxBinaryWriter, ChildrenAndEmptyNodesEndWithANullRecord) {
  Node parent{"P", {std::int32_t{1}}, {}};
  parent.add("C", {std::int32_t{2}});
  const Node empty{"E", {}, {}};
  const std::string b = encode_binary({parent, empty}, uncompressed());
  const std::size_t p = kHeaderBytes;
  const std::size_t child = p + 14 + 5;
  const std::size_t child_end = child + 14 + 5;
  EXPECT_EQ(read_at<std::uint32_t>(b, child), child_end);
  const std::size_t p_end = child_end + 13;
  EXPECT_EQ(read_at<std::uint32_t>(b, p), p_end);
  EXPECT_EQ(b.substr(child_end, 13), std::string(13, '\0'));
  EXPECT_EQ(read_at<std::uint32_t>(b, p_end), p_end + 14 + 13);  // "E": header, name, null record
  EXPECT_EQ(read_at<std::uint32_t>(b, p_end + 4), 0u);
}

TEST(FbxBinaryWriter, ArraysAreRawBelowTheThresholdAndZlibAbove) {
  std::vector<double> values(100);
  for (std::size_t i = 0; i < values.size(); ++i) values[i] = 0.5 * static_cast<double>(i);
  const Node n{"A", {values, std::vector<std::int32_t>{3, -4}}, {}};
  EncodeOptions options;
  options.compress_min_bytes = 64;  // the doubles (800 bytes) are compressed, the ints (8) not
  const std::string b = encode_binary({n}, options);
  std::size_t at = kHeaderBytes + 14;
  ASSERT_EQ(b[at], 'd');
  EXPECT_EQ(read_at<std::uint32_t>(b, at + 1), 100u);
  EXPECT_EQ(read_at<std::uint32_t>(b, at + 5), 1u);
  const std::uint32_t packed_bytes = read_at<std::uint32_t>(b, at + 9);
  std::vector<double> unpacked(100);
  uLongf unpacked_bytes = 800;
  ASSERT_EQ(uncompress(reinterpret_cast<Bytef*>(unpacked.data()), &unpacked_bytes,
                       reinterpret_cast<const Bytef*>(b.data() + at + 13), packed_bytes),
            Z_OK);
  EXPECT_EQ(unpacked_bytes, 800u);
  EXPECT_EQ(unpacked, values);
  at += 13 + packed_bytes;
  ASSERT_EQ(b[at], 'i');
  EXPECT_EQ(read_at<std::uint32_t>(b, at + 1), 2u);
  EXPECT_EQ(read_at<std::uint32_t>(b, at + 5), 0u);
  EXPECT_EQ(read_at<std::uint32_t>(b, at + 9), 8u);
  EXPECT_EQ(read_at<std::int32_t>(b, at + 13), 3);
  EXPECT_EQ(read_at<std::int32_t>(b, at + 17), -4);
}

TEST(FbxBinaryWriter, ThrowsInvalidInputForANameOver255Bytes) {
  EXPECT_THROW((void)encode_binary({Node{std::string(256, 'x'), {}, {}}}), InvalidInput);
}

}  // namespace
}  // namespace relief::fbx

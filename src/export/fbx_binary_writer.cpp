#include "export/fbx_binary_writer.h"

#include <libdeflate.h>

#include <bit>
#include <cstring>
#include <limits>
#include <memory>
#include <type_traits>

#include "relief/core/errors.h"

namespace relief::fbx {
namespace {

constexpr std::size_t kNullRecordBytes = 13;  // end offset, property count, byte length, name length

// Appends the little-endian bytes of an arithmetic value (x86/ARM hosts are little-endian;
// checked at compile time below).
template <typename T>
void put(std::string& out, T value) {
  static_assert(std::is_arithmetic_v<T>);
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  out.append(bytes, sizeof(T));
}
static_assert(std::endian::native == std::endian::little, "the FBX encoder assumes a little-endian host");

// Overwrites a uint32 at `offset` (end offsets and property byte lengths known only afterwards).
void patch_u32(std::string& out, std::size_t offset, std::size_t value) {
  if (value > std::numeric_limits<std::uint32_t>::max()) {
    throw InvalidInput("FBX: the file would exceed 4 GiB, beyond the 32-bit offsets of FBX 7.4");
  }
  const auto v = static_cast<std::uint32_t>(value);
  std::memcpy(out.data() + offset, &v, sizeof v);
}

void put_u32(std::string& out, std::size_t value) {
  put(out, std::uint32_t{0});
  patch_u32(out, out.size() - 4, value);
}

void put_sized_bytes(std::string& out, const std::string& bytes) {
  put_u32(out, bytes.size());
  out += bytes;
}

// zlib streams (what FBX's array encoding 1 holds) by libdeflate at level 1: the same size as
// zlib's fastest level in 2.5 times less time (0.17 against 0.42 s for the NE scene's arrays).
class Compressor {
 public:
  Compressor() : c_(libdeflate_alloc_compressor(1), libdeflate_free_compressor) {
    if (!c_) throw InvalidInput("FBX: libdeflate could not allocate a compressor");
  }
  std::string zlib(const void* data, std::size_t bytes) {
    std::string packed(libdeflate_zlib_compress_bound(c_.get(), bytes), '\0');
    const std::size_t n = libdeflate_zlib_compress(c_.get(), data, bytes, packed.data(), packed.size());
    if (n == 0)
      throw InvalidInput("FBX: libdeflate failed to compress an array of " + std::to_string(bytes) +
                         " bytes");
    packed.resize(n);
    return packed;
  }

 private:
  std::unique_ptr<libdeflate_compressor, void (*)(libdeflate_compressor*)> c_;
};

// Array payload: count, encoding, byte length, then raw or zlib-deflated elements.
template <typename T>
void put_array(std::string& out, const std::vector<T>& values, const EncodeOptions& options) {
  const std::size_t raw_bytes = values.size() * sizeof(T);
  put_u32(out, values.size());
  if (raw_bytes >= options.compress_min_bytes && raw_bytes > 0) {
    Compressor compressor;
    put(out, std::uint32_t{1});
    put_sized_bytes(out, compressor.zlib(values.data(), raw_bytes));
    return;
  }
  put(out, std::uint32_t{0});
  put_u32(out, raw_bytes);
  out.append(reinterpret_cast<const char*>(values.data()), raw_bytes);
}

void put_property(std::string& out, const Property& property, const EncodeOptions& options) {
  std::visit(
      [&](const auto& v) {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, std::int16_t>) {
          out += 'Y';
          put(out, v);
        } else if constexpr (std::is_same_v<T, bool>) {
          out += 'C';
          out += v ? '\x01' : '\x00';
        } else if constexpr (std::is_same_v<T, std::int32_t>) {
          out += 'I';
          put(out, v);
        } else if constexpr (std::is_same_v<T, float>) {
          out += 'F';
          put(out, v);
        } else if constexpr (std::is_same_v<T, double>) {
          out += 'D';
          put(out, v);
        } else if constexpr (std::is_same_v<T, std::int64_t>) {
          out += 'L';
          put(out, v);
        } else if constexpr (std::is_same_v<T, std::string>) {
          out += 'S';
          put_sized_bytes(out, v);
        } else if constexpr (std::is_same_v<T, Raw>) {
          out += 'R';
          put_sized_bytes(out, v.bytes);
        } else if constexpr (std::is_same_v<T, std::vector<std::int32_t>>) {
          out += 'i';
          put_array(out, v, options);
        } else if constexpr (std::is_same_v<T, std::vector<std::int64_t>>) {
          out += 'l';
          put_array(out, v, options);
        } else if constexpr (std::is_same_v<T, std::vector<float>>) {
          out += 'f';
          put_array(out, v, options);
        } else {
          static_assert(std::is_same_v<T, std::vector<double>>);
          out += 'd';
          put_array(out, v, options);
        }
      },
      property);
}

void put_null_record(std::string& out) {
  out.append(kNullRecordBytes, '\0');
}

void put_node(std::string& out, const Node& node, const EncodeOptions& options) {
  if (node.name.size() > 255) throw InvalidInput("FBX: node name longer than 255 bytes: " + node.name);
  const std::size_t start = out.size();
  put(out, std::uint32_t{0});  // end offset, patched below
  put_u32(out, node.properties.size());
  put(out, std::uint32_t{0});  // property list bytes, patched below
  out += static_cast<char>(node.name.size());
  out += node.name;
  const std::size_t properties_start = out.size();
  for (const Property& p : node.properties) put_property(out, p, options);
  patch_u32(out, start + 8, out.size() - properties_start);
  for (const Node& child : node.children) put_node(out, child, options);
  if (!node.children.empty() || node.properties.empty()) put_null_record(out);
  patch_u32(out, start, out.size());
}

}  // namespace

Node& Node::add(std::string child_name, std::vector<Property> child_properties) {
  children.push_back(Node{std::move(child_name), std::move(child_properties), {}});
  return children.back();
}

Node& Node::add_one(std::string child_name, Property property) {
  Node& child = add(std::move(child_name));
  child.properties.push_back(std::move(property));
  return child;
}

std::string encode_binary(const std::vector<Node>& top_level, const EncodeOptions& options) {
  std::string out("Kaydara FBX Binary  \0\x1a\0", 23);
  put(out, kVersion);
  for (const Node& node : top_level) put_node(out, node, options);
  put_null_record(out);

  // Footer as Blender writes it (the FBX SDK and Blender accept it; assimp ignores it):
  // footer id, 4 zero bytes, zero padding to a multiple of 16 (a full 16 when aligned),
  // version, 120 zero bytes, closing magic.
  static constexpr unsigned char kFooterId[16] = {0xfa, 0xbc, 0xab, 0x09, 0xd0, 0xc8, 0xd4, 0x66,
                                                  0xb1, 0x76, 0xfb, 0x83, 0x1c, 0xf7, 0x26, 0x7e};
  static constexpr unsigned char kClosingMagic[16] = {0xf8, 0x5a, 0x8c, 0x6a, 0xde, 0xf5, 0xd9, 0x7e,
                                                      0xec, 0xe9, 0x0c, 0xe3, 0x75, 0x8f, 0x29, 0x0b};
  out.append(reinterpret_cast<const char*>(kFooterId), sizeof kFooterId);
  out.append(4, '\0');
  const std::size_t padding = 16 - out.size() % 16;  // 16 when already aligned
  out.append(padding, '\0');
  put(out, kVersion);
  out.append(120, '\0');
  out.append(reinterpret_cast<const char*>(kClosingMagic), sizeof kClosingMagic);
  if (out.size() > std::numeric_limits<std::uint32_t>::max()) {
    throw InvalidInput("FBX: the file would exceed 4 GiB, beyond the 32-bit offsets of FBX 7.4");
  }
  return out;
}

}  // namespace relief::fbx

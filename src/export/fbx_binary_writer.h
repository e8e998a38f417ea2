#pragma once
// Encoder of the binary FBX container (version 7400, the FBX 2014/2015 layout with 32-bit
// offsets): a tree of named node records, each with a list of typed properties. This file knows
// the bytes only; what the nodes mean (geometry, models, connections) is fbx_scene_writer.h.
// relief writes its own FBX because Debian's assimp 5.2.5 writes binary FBX that neither assimp
// nor Blender can read back.
//
// Layout written (all integers little-endian):
//   header   "Kaydara FBX Binary  \0" 0x1a 0x00, uint32 version
//   node     uint32 end_offset (absolute), uint32 property_count, uint32 property_bytes,
//            uint8 name_length, name, properties, children, then a 13-byte null record when
//            the node has children or no property (as the FBX SDK and Blender do)
//   property type code ('Y','C','I','F','D','L','S','R', arrays 'i','l','f','d') + payload;
//            arrays are uint32 count, uint32 encoding (0 raw, 1 zlib), uint32 byte length
//   footer   the top-level list's null record, then the fixed footer Blender writes (footer id,
//            padding to 16 bytes, version, 120 zero bytes, closing magic).

#include <cstdint>
#include <string>
#include <variant>
#include <vector>

namespace relief::fbx {

inline constexpr std::uint32_t kVersion = 7400;

/// Raw bytes ('R'), to tell them apart from a string ('S') in a Property.
struct Raw {
  std::string bytes;
};

/// One typed property of a node: int16 'Y', bool 'C', int32 'I', float 'F', double 'D',
/// int64 'L', string 'S', raw 'R', arrays int32 'i', int64 'l', float 'f', double 'd'.
using Property = std::variant<std::int16_t, bool, std::int32_t, float, double, std::int64_t, std::string, Raw,
                              std::vector<std::int32_t>, std::vector<std::int64_t>, std::vector<float>,
                              std::vector<double>>;

/// A node record: name, properties, nested nodes.
struct Node {
  std::string name;
  std::vector<Property> properties;
  std::vector<Node> children;

  /// Appends a child and returns it (for building trees in place).
  Node& add(std::string child_name, std::vector<Property> child_properties = {});
  /// Appends a child with one property moved in: for arrays (a braced list's elements are
  /// copied, and a city's vertex arrays are tens of MB).
  Node& add_one(std::string child_name, Property property);
};

struct EncodeOptions {
  /// Arrays of at least this many bytes are zlib-compressed (encoding 1); 0 compresses all,
  /// SIZE_MAX none. The FBX SDK compresses arrays above 128 bytes too.
  std::size_t compress_min_bytes = 128;
};

/// The complete file: header, the top-level nodes, null record and footer.
/// Throws InvalidInput when a name is longer than 255 bytes or the file would exceed 4 GiB.
[[nodiscard]] std::string encode_binary(const std::vector<Node>& top_level,
                                        const EncodeOptions& options = {});

}  // namespace relief::fbx

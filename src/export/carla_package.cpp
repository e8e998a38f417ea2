#include "relief/export/carla_package.h"

#include <libdeflate.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cstring>
#include <memory>
#include <optional>
#include <set>
#include <utility>

#include <nlohmann/json.hpp>

#include "relief/core/errors.h"

namespace relief {
namespace {

struct Tile {
  int x = 0, y = 0;
  const EncodedFile* file = nullptr;
};

// The input checked: a standard map's one FBX, or a large map's tiles sorted by (X, Y).
struct Layout {
  const EncodedFile* source = nullptr;
  std::vector<Tile> tiles;
};

std::string_view without_prefix(std::string_view text, std::string_view prefix) {
  return text.starts_with(prefix) ? text.substr(prefix.size()) : std::string_view{};
}

// A decimal integer >= 0 with nothing else: "0", "12"; not "", "+1", "1a".
std::optional<int> parse_index(std::string_view text) {
  int value = 0;
  if (text.empty() || text.size() > 9 || text[0] < '0' || text[0] > '9') return std::nullopt;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc{} || end != text.data() + text.size()) return std::nullopt;
  return value;
}

// X and Y of "NAME_Tile_X_Y.fbx".
std::optional<std::pair<int, int>> parse_tile(std::string_view filename, const std::string& name) {
  std::string_view rest = without_prefix(filename, name + "_Tile_");
  if (rest.empty() || !rest.ends_with(".fbx")) return std::nullopt;
  rest.remove_suffix(4);
  const std::size_t cut = rest.find('_');
  if (cut == std::string_view::npos) return std::nullopt;
  const auto x = parse_index(rest.substr(0, cut));
  const auto y = parse_index(rest.substr(cut + 1));
  if (!x || !y) return std::nullopt;
  return std::make_pair(*x, *y);
}

Layout check(const CarlaPackageInput& in) {
  if (!is_valid_carla_map_name(in.map_name)) {
    throw InvalidInput("CARLA package: map name '" + in.map_name +
                       "' is not valid (letters, digits, '_' and '-' only, at most 64)");
  }
  if (in.fbx_files.empty()) throw InvalidInput("CARLA package: no FBX file");
  if (in.mtime_s < 0) throw InvalidInput("CARLA package: modification time before 1970");
  Layout layout;
  if (in.tile_size_m == 0) {
    if (in.fbx_files.size() != 1 || in.fbx_files[0].filename != in.map_name + ".fbx") {
      throw InvalidInput("CARLA package: a standard map takes exactly one FBX named '" + in.map_name +
                         ".fbx'");
    }
    layout.source = in.fbx_files.data();
    return layout;
  }
  if (in.tile_size_m < 1 || in.tile_size_m > kCarlaMaxTileSizeM) {
    throw InvalidInput("CARLA package: tile size " + std::to_string(in.tile_size_m) + " m is not in 1.." +
                       std::to_string(kCarlaMaxTileSizeM));
  }
  std::set<std::pair<int, int>> seen;
  for (const EncodedFile& file : in.fbx_files) {
    const auto xy = parse_tile(file.filename, in.map_name);
    if (!xy) {
      throw InvalidInput("CARLA package: '" + file.filename + "' is not named " + in.map_name +
                         "_Tile_X_Y.fbx");
    }
    if (!seen.insert(*xy).second) throw InvalidInput("CARLA package: tile '" + file.filename + "' twice");
    layout.tiles.push_back(Tile{xy->first, xy->second, &file});
  }
  std::sort(layout.tiles.begin(), layout.tiles.end(),
            [](const Tile& a, const Tile& b) { return std::tie(a.x, a.y) < std::tie(b.x, b.y); });
  return layout;
}

std::string json_of(const CarlaPackageInput& in, const Layout& layout) {
  using Json = nlohmann::ordered_json;
  const std::string& name = in.map_name;
  // Keys in the order of CARLA's documentation; Import.py reads them by name.
  Json map{{"name", name}};
  if (layout.source != nullptr) {
    map["source"] = "./" + name + "/" + name + ".fbx";
    map["use_carla_materials"] = in.use_carla_materials;
    map["xodr"] = "./" + name + "/" + name + ".xodr";
  } else {
    map["xodr"] = "./" + name + ".xodr";
    map["use_carla_materials"] = in.use_carla_materials;
    map["tile_size"] = in.tile_size_m;
    Json tiles = Json::array();
    for (const Tile& t : layout.tiles) tiles.push_back("./" + t.file->filename);
    map["tiles"] = std::move(tiles);
  }
  const Json package{{"maps", Json::array({std::move(map)})}, {"props", Json::array()}};
  return package.dump(2) + "\n";
}

// One archive entry; no bytes: a directory.
struct Entry {
  std::string path;
  const std::string* bytes = nullptr;
};

std::vector<Entry> entries_of(const CarlaPackageInput& in, const Layout& layout, const std::string& json) {
  const std::string root = in.map_name + "/";
  std::vector<Entry> entries{{root}, {root + in.map_name + ".json", &json}};
  if (layout.source != nullptr) {
    const std::string dir = root + in.map_name + "/";
    entries.push_back({dir});
    entries.push_back({dir + layout.source->filename, &layout.source->bytes});
    entries.push_back({dir + in.map_name + ".xodr", &in.xodr});
  } else {
    entries.push_back({root + in.map_name + ".xodr", &in.xodr});
    for (const Tile& t : layout.tiles) entries.push_back({root + t.file->filename, &t.file->bytes});
  }
  return entries;
}

// --- POSIX ustar (pax's "ustar" interchange format, IEEE Std 1003.1) --------------------------

constexpr std::size_t kBlock = 512;
constexpr std::size_t kRecord = 20 * kBlock;  // GNU tar's default blocking factor

// `value` as octal digits filling `width` - 1 bytes, then NUL.
void put_octal(char* field, std::size_t width, std::uint64_t value, const std::string& path) {
  for (std::size_t i = width - 1; i-- > 0;) {
    field[i] = static_cast<char>('0' + (value & 7u));
    value >>= 3;
  }
  if (value != 0) throw InvalidInput("CARLA package: '" + path + "' is too large for a tar entry");
  field[width - 1] = '\0';
}

// Splits `path` into ustar's name (<= 100 bytes) and prefix (<= 155 bytes) at a '/'.
std::pair<std::string, std::string> split_path(const std::string& path) {
  if (path.size() <= 100) return {path, ""};
  for (std::size_t cut = path.find('/'); cut != std::string::npos; cut = path.find('/', cut + 1)) {
    if (cut <= 155 && path.size() - cut - 1 <= 100) return {path.substr(cut + 1), path.substr(0, cut)};
  }
  throw InvalidInput("CARLA package: path '" + path + "' is too long for a tar entry");
}

void append_header(std::string& out, const Entry& e, std::int64_t mtime_s) {
  std::array<char, kBlock> h{};
  const auto [name, prefix] = split_path(e.path);
  std::memcpy(h.data(), name.data(), name.size());
  const bool dir = e.bytes == nullptr;
  put_octal(h.data() + 100, 8, dir ? 0755u : 0644u, e.path);  // mode
  put_octal(h.data() + 108, 8, 0, e.path);                    // uid
  put_octal(h.data() + 116, 8, 0, e.path);                    // gid
  put_octal(h.data() + 124, 12, dir ? 0u : e.bytes->size(), e.path);
  put_octal(h.data() + 136, 12, static_cast<std::uint64_t>(mtime_s), e.path);
  h[156] = dir ? '5' : '0';                 // typeflag
  std::memcpy(h.data() + 257, "ustar", 6);  // magic, NUL-terminated
  std::memcpy(h.data() + 263, "00", 2);     // version
  put_octal(h.data() + 329, 8, 0, e.path);  // devmajor
  put_octal(h.data() + 337, 8, 0, e.path);  // devminor
  std::memcpy(h.data() + 345, prefix.data(), prefix.size());
  // Checksum: the unsigned sum of the header's bytes with the checksum field taken as spaces,
  // six octal digits, NUL, space.
  std::memset(h.data() + 148, ' ', 8);
  unsigned sum = 0;
  for (const char c : h) sum += static_cast<unsigned char>(c);
  put_octal(h.data() + 148, 7, sum, e.path);
  h[155] = ' ';
  out.append(h.data(), h.size());
}

std::string tar(const std::vector<Entry>& entries, std::int64_t mtime_s) {
  std::size_t size = 2 * kBlock;
  for (const Entry& e : entries)
    size += kBlock + (e.bytes ? (e.bytes->size() + kBlock - 1) / kBlock * kBlock : 0);
  size = (size + kRecord - 1) / kRecord * kRecord;
  std::string out;
  out.reserve(size);
  for (const Entry& e : entries) {
    append_header(out, e, mtime_s);
    if (e.bytes == nullptr) continue;
    out += *e.bytes;
    out.append((kBlock - e.bytes->size() % kBlock) % kBlock, '\0');
  }
  // The end: two zero blocks, then zeros to a whole record.
  out.append(size - out.size(), '\0');
  return out;
}

// gzip (RFC 1952) by libdeflate at level 6; its header has no name and time 0.
std::string gzip(const std::string& bytes) {
  const std::unique_ptr<libdeflate_compressor, decltype(&libdeflate_free_compressor)> c(
      libdeflate_alloc_compressor(6), libdeflate_free_compressor);
  if (!c) throw InvalidInput("CARLA package: libdeflate could not allocate a compressor");
  std::string packed(libdeflate_gzip_compress_bound(c.get(), bytes.size()), '\0');
  const std::size_t n =
      libdeflate_gzip_compress(c.get(), bytes.data(), bytes.size(), packed.data(), packed.size());
  if (n == 0) throw InvalidInput("CARLA package: gzip compression failed");
  packed.resize(n);
  return packed;
}

}  // namespace

bool is_valid_carla_map_name(std::string_view name) {
  if (name.empty() || name.size() > 64) return false;
  return std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-';
  });
}

std::string carla_package_json(const CarlaPackageInput& input) {
  return json_of(input, check(input));
}

std::vector<std::string> carla_package_entries(const CarlaPackageInput& input) {
  const Layout layout = check(input);
  const std::string json = json_of(input, layout);
  std::vector<std::string> paths;
  for (const Entry& e : entries_of(input, layout, json)) paths.push_back(e.path);
  return paths;
}

std::vector<std::string> carla_tile_grid_gaps(const CarlaPackageInput& input) {
  const Layout layout = check(input);
  std::vector<std::string> gaps;
  if (layout.tiles.empty()) return gaps;
  int max_x = 0, max_y = 0;
  std::set<std::pair<int, int>> present;
  for (const Tile& t : layout.tiles) {
    max_x = std::max(max_x, t.x);
    max_y = std::max(max_y, t.y);
    present.emplace(t.x, t.y);
  }
  for (int y = 0; y <= max_y; ++y)
    for (int x = 0; x <= max_x; ++x)
      if (!present.contains({x, y})) gaps.push_back(std::to_string(x) + " " + std::to_string(y));
  return gaps;
}

std::string encode_carla_package(const CarlaPackageInput& input) {
  const Layout layout = check(input);
  const std::string json = json_of(input, layout);
  return gzip(tar(entries_of(input, layout, json), input.mtime_s));
}

}  // namespace relief

#pragma once
// Content hashes (SHA-256) of input files, so that work done on them can be recognised as done:
// a region tile is rebuilt only when its inputs or options changed.

#include <filesystem>
#include <string>
#include <string_view>

namespace relief {

/// Lower-case hex SHA-256 of `bytes`.
[[nodiscard]] std::string sha256_hex(std::string_view bytes);

/// Lower-case hex SHA-256 of the file's content, read in blocks (constant memory). A GDAL
/// virtual path ("/vsizip/A.zip/B.hgt", "/vsigzip/C.gz") is hashed by its container file, the
/// first component of the path that is a regular file. Throws IoError when it cannot be read.
[[nodiscard]] std::string sha256_of_file(const std::filesystem::path& path);

/// An input path that reads the same file from any working directory (a plan's tiles are built
/// wherever its builder runs: another directory, a cluster's worker): a relative path to an
/// existing file made absolute; a GDAL virtual path whose container is relative to an existing
/// file ("/vsizip/a.zip/b.hgt") with that container made absolute ("/vsizip//work/a.zip/b.hgt");
/// anything else (absolute, not found, a URL) as given.
[[nodiscard]] std::string absolute_input_path(const std::string& path);

}  // namespace relief

#pragma once
// Private to the demand module: the small CSV tables it reads (traffic counts, OD matrices):
// comma-separated, a header line, fields trimmed, blank lines and lines starting with '#'
// skipped; each row knows where it stands for messages.

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace relief::detail {

struct CsvRow {
  std::vector<std::string> fields;
  int line = 0;
  std::string where;  ///< "'FILE' line N"
};

struct CsvTable {
  std::filesystem::path path;
  std::vector<std::string> header;
  std::vector<CsvRow> rows;

  /// The header's column `name`, or InvalidInput naming the file and `expected` (the header).
  [[nodiscard]] std::size_t column(const std::string& name, const std::string& expected) const;
};

/// Reads `path` (`what` names it in the IoError when it cannot be read). Rows with fewer fields
/// than the header are InvalidInput naming the line.
[[nodiscard]] CsvTable read_csv_table(const std::filesystem::path& path, const std::string& what);

std::string trim(const std::string& s);

}  // namespace relief::detail

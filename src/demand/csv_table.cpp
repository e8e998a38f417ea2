#include "demand/csv_table.h"

#include <algorithm>
#include <fstream>
#include <sstream>

#include "relief/core/errors.h"

namespace relief::detail {
namespace {

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream in(line);
  for (std::string f; std::getline(in, f, ',');) fields.push_back(trim(f));
  return fields;
}

}  // namespace

std::string trim(const std::string& s) {
  const std::size_t a = s.find_first_not_of(" \t\r"), b = s.find_last_not_of(" \t\r");
  return a == std::string::npos ? std::string() : s.substr(a, b - a + 1);
}

std::size_t CsvTable::column(const std::string& name, const std::string& expected) const {
  const auto it = std::find(header.begin(), header.end(), name);
  if (it == header.end())
    throw InvalidInput("'" + path.string() + "' line 1: no column '" + name + "' (" + expected + ")");
  return static_cast<std::size_t>(it - header.begin());
}

CsvTable read_csv_table(const std::filesystem::path& path, const std::string& what) {
  std::ifstream in(path);
  if (!in) throw IoError("cannot read the " + what + " '" + path.string() + "'");
  CsvTable table;
  table.path = path;
  std::string line;
  std::getline(in, line);
  table.header = split(line);
  for (int number = 2; std::getline(in, line); ++number) {
    const std::string text = trim(line);
    if (text.empty() || text.starts_with('#')) continue;
    CsvRow row{split(line), number, "'"};  // not "'" + ...: GCC 12's false -Wrestrict (bug 105329)
    row.where += path.string();
    row.where += "' line ";
    row.where += std::to_string(number);
    if (row.fields.size() < table.header.size())
      throw InvalidInput(row.where + ": " + std::to_string(row.fields.size()) + " fields, the header has " +
                         std::to_string(table.header.size()));
    table.rows.push_back(std::move(row));
  }
  return table;
}

}  // namespace relief::detail

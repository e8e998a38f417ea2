// relief_write_corpus: writes a case of the stress corpus (support/corpus.h) to a folder, for
// benchmarks and for building the corpus by hand with the relief CLI. Prints the case's files
// and size as one JSON line.
//   relief_write_corpus mountain CELL_M DIR
//   relief_write_corpus mountain-range COPIES CELL_M DIR
//   relief_write_corpus old-town DIR
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <iostream>
#include <string>

#include <nlohmann/json.hpp>

#include "support/corpus.h"

namespace {

int usage() {
  std::cerr << "usage: relief_write_corpus mountain CELL_M DIR\n"
               "       relief_write_corpus mountain-range COPIES CELL_M DIR\n"
               "       relief_write_corpus old-town DIR\n";
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  using relief::test::CorpusCase;
  const std::string which = argc > 1 ? argv[1] : "";
  try {
    CorpusCase c;
    std::filesystem::path dir;
    if (which == "mountain" && argc == 4) {
      dir = argv[3];
      std::filesystem::create_directories(dir);
      c = relief::test::make_mountain(std::stod(argv[2]), dir);
    } else if (which == "mountain-range" && argc == 5) {
      dir = argv[4];
      std::filesystem::create_directories(dir);
      c = relief::test::make_mountain_range(std::stoi(argv[2]), std::stod(argv[3]), dir);
    } else if (which == "old-town" && argc == 3) {
      dir = argv[2];
      std::filesystem::create_directories(dir);
      c = relief::test::make_old_town(dir);
    } else {
      return usage();
    }
    nlohmann::json out{{"osm", c.osm.string()}, {"dem", c.dem}, {"ways", c.ways}, {"road_km", c.road_km}};
    if (c.bbox) out["bbox"] = {c.bbox->min_lon, c.bbox->min_lat, c.bbox->max_lon, c.bbox->max_lat};
    std::cout << out.dump() << "\n";
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "relief_write_corpus: " << e.what() << "\n";
    return 1;
  }
}

#pragma once
// Private to the export module: the sight summary as JSON (report.json "sight", and the file
// `relief sight` writes).

#include <nlohmann/json.hpp>

#include "relief/export/sight_writer.h"

namespace relief {

[[nodiscard]] nlohmann::ordered_json sight_json(const SightSummary& s);

}  // namespace relief

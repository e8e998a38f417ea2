#pragma once
// The region's SUMO network, from the merged RoadModel: the same chain as one build's
// (export/sumo_net_build.h: plain network, netconvert over it, drape, check), so that the
// region's lanes lie on the merged OpenDRIVE surface as a build's lie on its own. The roads carry
// their OSM ways, highway class and traffic lights in the tiles' .xodr files, so nothing of the
// tiles' OSM is read again.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "relief/core/atomic_file.h"
#include "relief/core/diagnostics.h"
#include "relief/export/quality_gates.h"
#include "relief/export/sumo_network.h"
#include "relief/roads/profile_fit.h"
#include "relief/roads/road_model.h"

namespace relief::detail {

/// Each road's grade cap under `fit` (grade_limit by its highway class), -1 for a road without
/// one (a connecting road: the larger cap of the roads it joins, linked_grade_cap). A build
/// also lowers a tunnel's cap; the .xodr does not say which roads are tunnels, so a tunnel here
/// keeps its class's cap and its steps are judged a little more leniently.
[[nodiscard]] std::vector<double> model_grade_caps(const RoadModel& model, const ProfileFitOptions& fit);

/// Writes NAME.net.xml, NAME.{nod,edg,con}.xml and NAME.sumo_mapping.json of `model` into
/// `files` under `dir` (netconvert works in a scratch folder there); appends them to `written`
/// and a failure of the build's SUMO gates (`gates`) to `failed_gates`. Returns report.json's
/// "sumo" object.
nlohmann::json merge_sumo_net(const RoadModel& model, const SumoOptions& options, const GateThresholds& gates,
                              const std::filesystem::path& dir, const std::string& name, OutputSet& files,
                              std::vector<std::filesystem::path>& written,
                              std::vector<std::string>& failed_gates, Diagnostics& diagnostics);

}  // namespace relief::detail

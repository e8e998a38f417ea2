#pragma once
// Reads an OpenDRIVE file (ours or anyone's, 1.4 to 1.8) into a RoadModel: planView (line, arc,
// spiral, poly3, paramPoly3), elevationProfile, lateralProfile superelevation, laneOffset, lane
// sections with lane widths and road marks, road links and junction connections. Lane height
// records, objects and signals are ignored.
//
// Mapping: the frame is relief's own (<userData code="relief:crs"/"relief:origin">) when present,
// else GeoFrame(geoReference PROJ string, origin 0), else the default frame. A deprecated poly3
// v(u) becomes an exactly equivalent normalized paramPoly3 u = U p, v = v(U p), U chosen so that
// the arc length is the record length. Zero-length geometry records are skipped. Records, pieces,
// sections and lanes are sorted (lanes innermost first); lane width pieces keep s = sOffset. Only
// the first roadMark of a lane is kept; "broken broken" and "botts dots" read as broken, other
// unknown mark types as none. Speeds are converted to m/s ("no limit" -> none). A direct
// junction's linkedRoad is read as the connecting road. Ids must be integers.

#include <filesystem>
#include <string_view>

#include "relief/roads/road_model.h"

namespace relief {

/// Throws IoError when the file cannot be read, InvalidInput when it is not OpenDRIVE or a record
/// is malformed (the message names the file, the road id and the element): not well-formed XML,
/// no <OpenDRIVE> root or <road>, a road without planView geometry or lanes, a missing or
/// non-finite number, a non-integer id, lanes given by <border> records (not supported).
[[nodiscard]] RoadModel read_opendrive(const std::filesystem::path& path);

/// The same from a string; `source` names it in messages.
[[nodiscard]] RoadModel parse_opendrive(std::string_view xml, std::string_view source = "<string>");

}  // namespace relief

#pragma once
// OpenDRIVE (.xodr) serialisation of a RoadModel, valid against the ASAM schema of the chosen
// version (1.7 by default; 1.4 for older readers; 1.8). Coordinates are the model's local frame;
// the header's geoReference is the frame's PROJ string, so any reader can map back to lon/lat.
//
// The header carries north/south/east/west (bounds of the reference lines, sampled every metre),
// the ODbL attribution (an XML comment, a <userData code="attribution">, and in 1.8 a <license>),
// <offset> 0 (1.7, 1.8) and relief's frame as <userData code="relief:crs"> / "relief:origin", from
// which roads/opendrive_reader.h restores the frame exactly. Element order follows the schemas:
// lanes left (ids descending), centre, right (-1, -2, ...). An empty elevation, superelevation or
// lane width is written as one record of 0 (the same function; 1.4 requires a width record); an
// empty lane offset is left out. Speeds are m/s, except in 1.4 whose schema takes whole numbers
// only: km/h, rounded. Numbers are printed with append_fixed (no locale, no "-0").

#include <ostream>
#include <string>

#include "relief/roads/road_model.h"

namespace relief {

struct OpenDriveOptions {
  int rev_minor = 7;  ///< OpenDRIVE 1.<rev_minor>: 4, 7 or 8
  std::string name;   ///< header name (default: the model's name)
  std::string date;   ///< header date, ISO 8601 (default: empty)
  std::string vendor = "relief";
  int decimals = 9;  ///< digits after the point for coordinates and coefficients
};

/// Writes the model. Throws InvalidInput, naming the road or junction, for a model OpenDRIVE
/// cannot express: no roads, a road without geometry or lane section, a first lane section that
/// does not start at 0, sections out of order, a left lane id <= 0 or right lane id >= 0, a lane
/// id twice in a section, a road type, lane type or mark colour the chosen version does not
/// define, a record length that prints as 0 at `decimals`, a junction without connections, NaN or
/// infinity anywhere; and for rev_minor other than 4, 7, 8 or decimals outside [0, 17].
void write_opendrive(std::ostream& out, const RoadModel& model, const OpenDriveOptions& options = {});

}  // namespace relief

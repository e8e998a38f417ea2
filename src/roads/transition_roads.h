#pragma once
// Private to the roads module: two roads meeting end to end (an attribute change: a lane or tag
// change, a bend at a node of two ways). Where one continues the other they link directly, lane
// to lane; otherwise a short transition road bends and widens from one to the other; where no
// lane leads from one into the other (two one-ways both arriving or both leaving) both end there.

#include <cstdint>
#include <vector>

#include "relief/core/diagnostics.h"
#include "relief/geometry/types.h"
#include "relief/roads/elevation_sampling.h"
#include "relief/roads/road_model.h"
#include "relief/roads/road_model_builder.h"
#include "relief/roads/road_network.h"

namespace relief::detail {

/// Whether traffic can pass between the two roads of an attribute change: not where two one-ways
/// both arrive or both leave (an extract's edge cutting through a merge leaves such nodes).
[[nodiscard]] bool has_passage(const RoadNetwork& network, const Junction& j);

/// Two roads meeting end to end link directly when one continues the other: straight enough that
/// their outermost lane borders meet within 2 mm, with the same lanes each way and the same lane
/// width. Otherwise (and where traffic can pass) a short transition road bends and widens from
/// one to the other.
[[nodiscard]] bool needs_transition(const RoadNetwork& network, const Junction& j);

/// How far a transition road at junction j reaches into both roads: from `reach` on, the least
/// (in steps of 25 %, at most max_trim_fraction of either road) at which the bend between the
/// two ends is no tighter than either road's minimum radius (what the reference line keeps at
/// an OSM vertex; the bend's radius is chord / (2 sin(turn / 2))), or else the one with the
/// widest bend. Reaching further stops where the transition would climb steeper than both roads
/// there (plus the connection allowance) and than it does at `reach`: the legs of a hairpin
/// drawn to one node can part in height faster than in plan.
[[nodiscard]] double transition_reach(const RoadNetwork& network, const std::vector<RoadProfile>& profiles,
                                      const Junction& j, double reach, const RoadModelOptions& options);

/// needs_transition for every network junction (1 where it holds).
[[nodiscard]] std::vector<std::uint8_t> transition_junctions(const RoadNetwork& network);

/// What became of a transition road (add_transition_road).
enum class TransitionOutcome {
  added,
  folds,     ///< a lane border on the inside of the bend within the margin of its centre, or beyond
  too_steep  ///< a lane centre climbs steeper than the lane grade allowed
};

/// A road from road `a`'s end at a junction to road `b`'s end there (no OpenDRIVE junction: two
/// ends only). Its right lanes carry the traffic from a to b, its left lanes the traffic back;
/// lanes missing on one side taper to width 0; the lane offset, heights and slopes blend from
/// a's to b's with cubics, so every linked lane border meets exactly. Its roll lays it on the
/// plane of `gradient`. Appended to model.roads; a's and b's links and lane links point to it.
/// `a_ref` is an element of model.roads, `b_id` the id of another. Where the corner is too
/// tight for the lanes (a border on the inside of the bend within `margin_m` of its centre, or
/// beyond it, where the lofted lanes would fold over themselves), or a lane centre climbs
/// steeper than `max_lane_grade` over any 0.2 m of its own length (the inner lane of a tight
/// bend is much shorter than the reference line it climbs with), nothing is added or changed,
/// and it says which.
[[nodiscard]] TransitionOutcome add_transition_road(RoadModel& model, ModelRoad& a_ref, bool a_at_start,
                                                    int b_id, bool b_at_start, const Vec2& gradient,
                                                    double margin_m, double max_lane_grade);

/// Direct link, lane to lane, between two roads' ends: same direction (end meets start) pairs
/// right lanes with right lanes, opposite directions right with left.
void link_directly(ModelRoad& a, bool a_at_start, ModelRoad& b, bool b_at_start);

/// Reports (info) that the two roads of junction j meet in a bend too tight for a transition
/// road (`why`: its inner border within `radius_m` of the bend's centre, or a lane centre
/// steeper than `max_lane_grade`), and that the node is built as a junction.
void report_transition_as_junction(const Junction& j, const ModelRoad& a, const ModelRoad& b,
                                   TransitionOutcome why, double radius_m, double max_lane_grade,
                                   Diagnostics& diagnostics);

/// Reports two roads meeting at junction j without passage between them (codes::kModelNoPassage).
void report_no_passage(const Junction& j, const ModelRoad& a, const ModelRoad& b, Diagnostics& diagnostics);

}  // namespace relief::detail

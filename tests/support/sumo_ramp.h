#pragma once
// A RoadModel with an analytic answer for the SUMO tests: one 10 % ramp east along y = 0,
// z = 0.1 x, through one junction.

#include "relief/roads/road_model.h"

namespace relief::test {

/// Road 1 (x 0..100, a 3 m lane each way: 1 and -1), the connecting road 2 of junction 100
/// (x 100..110, right lane -1 only, linking lane -1 of road 1 to lane -1 of road 3) and road 3
/// (x 110..210, right lane -1 only). No lane offset: lane centres lie at y = +-1.5.
[[nodiscard]] RoadModel ramp_model();

/// The .net.xml netconvert would write for ramp_model(): lane centres at y = -1.5 (along s) and
/// y = +1.5 (against s) on the plane z = 0.1 x. The connection carries no params (as from
/// netconvert 1.15), so its internal lane :J_0_0 (x 100..110) is found through the model's
/// junction; its shape is relief's (the OpenDRIVE lane centre).
[[nodiscard]] const char* ramp_net_xml();

}  // namespace relief::test

#include "support/sumo_ramp.h"

namespace relief::test {
namespace {

LaneModel lane(int id, double width_m) {
  LaneModel l;
  l.id = id;
  l.width = CubicProfile({CubicPiece{0.0, {width_m, 0.0, 0.0, 0.0}}});
  return l;
}

// A straight road east along y = 0 from x = x0, rising 10 % from z0.
ModelRoad ramp_road(int id, double x0, double length, double z0) {
  ModelRoad road;
  road.id = id;
  PlanGeometry line;
  line.start = Vec2(x0, 0.0);
  line.length = length;
  road.plan = PlanView({line});
  road.elevation = CubicProfile({CubicPiece{0.0, {z0, 0.1, 0.0, 0.0}}});
  road.lane_offset = CubicProfile::constant(0.0);
  return road;
}

}  // namespace

RoadModel ramp_model() {
  ModelRoad r1 = ramp_road(1, 0.0, 100.0, 0.0);
  LaneSection s1;
  s1.left = {lane(1, 3.0)};
  s1.right = {lane(-1, 3.0)};
  r1.sections = {s1};
  r1.successor = RoadLink{RoadLink::Element::junction, 100, RoadLink::Contact::start};

  ModelRoad r2 = ramp_road(2, 100.0, 10.0, 10.0);
  r2.junction = 100;
  LaneSection s2;
  s2.right = {lane(-1, 3.0)};
  s2.right[0].predecessor = -1;
  s2.right[0].successor = -1;
  r2.sections = {s2};
  r2.predecessor = RoadLink{RoadLink::Element::road, 1, RoadLink::Contact::end};
  r2.successor = RoadLink{RoadLink::Element::road, 3, RoadLink::Contact::start};

  ModelRoad r3 = ramp_road(3, 110.0, 100.0, 11.0);
  LaneSection s3;
  s3.right = {lane(-1, 3.0)};
  r3.sections = {s3};
  r3.predecessor = RoadLink{RoadLink::Element::junction, 100, RoadLink::Contact::start};

  RoadModel model;
  model.roads = {r1, r2, r3};
  JunctionModel junction;
  junction.id = 100;
  JunctionConnection c;
  c.incoming_road = 1;
  c.connecting_road = 2;
  c.lane_links = {{-1, -1}};
  junction.connections = {c};
  model.junctions = {junction};
  return model;
}

const char* ramp_net_xml() {
  return R"(<net version="1.9">
  <edge id=":J_0" function="internal">
    <lane id=":J_0_0" index="0" speed="10" length="10.05" shape="100,-1.5,10 110,-1.5,11"/>
  </edge>
  <edge id="-1" from="J" to="A">
    <lane id="-1_0" index="0" speed="10" length="100.5" shape="100,1.5,10 0,1.5,0">
      <param key="odr.lane" value="1"/>
    </lane>
    <param key="odr.road" value="1"/>
  </edge>
  <edge id="1" from="A" to="J">
    <lane id="1_0" index="0" speed="10" length="100.5" shape="0,-1.5,0 100,-1.5,10">
      <param key="odr.lane" value="-1"/>
    </lane>
    <param key="odr.road" value="1"/>
  </edge>
  <edge id="3" from="J" to="B">
    <lane id="3_0" index="0" disallow="truck" speed="10" length="100.5" shape="110,-1.5,11 210,-1.5,21">
      <param key="odr.lane" value="-1"/>
    </lane>
    <param key="odr.road" value="3"/>
  </edge>
  <junction id="A" type="dead_end" x="0" y="0"/>
  <junction id="J" type="priority" x="105" y="0"/>
  <junction id="B" type="dead_end" x="210" y="0"/>
  <connection from="1" to="3" fromLane="0" toLane="0" shape="100,-1.5,10 110,-1.5,11" via=":J_0_0" dir="s" state="M"/>
  <connection from=":J_0" to="3" fromLane="0" toLane="0" dir="s" state="M"/>
</net>
)";
}

}  // namespace relief::test

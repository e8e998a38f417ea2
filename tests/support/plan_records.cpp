#include "support/plan_records.h"

namespace relief::test {

PlanGeometry line_record(double s, const Vec2& start, double heading, double length_m) {
  PlanGeometry g;
  g.kind = PlanGeometry::Kind::line;
  g.s = s;
  g.start = start;
  g.heading = heading;
  g.length = length_m;
  return g;
}

PlanGeometry arc_record(double s, const Vec2& start, double heading, double length_m, double curvature) {
  PlanGeometry g = line_record(s, start, heading, length_m);
  g.kind = PlanGeometry::Kind::arc;
  g.curvature = curvature;
  return g;
}

}  // namespace relief::test

// Rigid, fixed, flat wall segments of infinite mass (SPEC §2). A disc whose closest point on a
// segment is one of its ends touches that end as a point contact; where two segments of a
// polyline meet, the shared vertex belongs to the earlier segment only, so a disc resting on a
// convex vertex feels one contact, not two.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <string>
#include <vector>

#include "runout/scene.hpp"

namespace runout {

struct Segment {
  Eigen::Vector2d a, b;
  bool cap_a = true, cap_b = true;  // whether each end acts as a point contact
  bool bed = false;
  bool active = true;  // a removed wall (the released gate) stays listed so indices are stable
  int wall = 0;  // index of the WallDef it came from
};

// Closest point of a segment to p: parameter t in [0, 1] along a -> b.
struct SegmentProjection {
  Eigen::Vector2d point;
  double t = 0;
  bool at_free_end = false;  // t hit an end that does not act as a point contact
};

inline SegmentProjection project(const Segment& s, const Eigen::Vector2d& p) {
  const Eigen::Vector2d ab = s.b - s.a;
  const double len2 = ab.squaredNorm();
  double t = len2 > 0 ? (p - s.a).dot(ab) / len2 : 0.0;
  SegmentProjection out;
  if (t <= 0) { t = 0; out.at_free_end = !s.cap_a; }
  if (t >= 1) { t = 1; out.at_free_end = !s.cap_b; }
  out.t = t;
  out.point = s.a + t * ab;
  return out;
}

// Distance from p to the segment including both ends (geometry, ignores caps).
inline double distance_to(const Segment& s, const Eigen::Vector2d& p) {
  const Eigen::Vector2d ab = s.b - s.a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - s.a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (s.a + t * ab - p).norm();
}

// Splits wall polylines into segments, assigning each shared vertex to one segment.
std::vector<Segment> make_segments(const std::vector<WallDef>& walls);

}  // namespace runout

// Rigid, fixed, flat wall segments of infinite mass (SPEC §2).
//
// A one-sided segment (WallInside left/right) is a face of a closed container: a disc whose
// centre lies in front of the line touches it along the line; a disc whose centre has been
// pressed past the line, but not by more than its own diameter, is still pushed back to the
// inside, with the overlap measured from the inside (r + depth). That is what makes a segment
// rigid: a squeezed disc cannot pop out through the wall, as it does through a two-sided
// plate once its overlap exceeds its radius. An end of a segment is a point contact only
// where it is exposed: a free end of a polyline, or a convex corner (owned by one of the two
// segments). At a concave corner the two faces meet and neither end acts as a point; behind
// such a corner the two segments share the outside along the corner's bisector, so a centre
// pressed into the corner is always pushed back by exactly one face.
//
// A two-sided segment (WallInside both) is a thin plate: the closest point of the segment acts,
// ends included; where two segments of a polyline meet, the shared vertex belongs to the
// earlier one only, so a disc resting on a vertex feels one contact, not two.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "runout/scene.hpp"

namespace runout {

struct Segment {
  Eigen::Vector2d a, b;
  bool cap_a = true, cap_b = true;  // whether each end acts as a point contact
  // One-sided: unit normal pointing to the discs' side; zero for a two-sided plate.
  Eigen::Vector2d inside{0.0, 0.0};
  // One-sided, behind the line: a centre belongs to this segment while
  // (p - a)·behind_a >= 0 and (p - b)·behind_b >= 0. Perpendicular to the segment at a free end
  // or a convex corner, along the outside bisector at a concave corner.
  Eigen::Vector2d behind_a{0.0, 0.0}, behind_b{0.0, 0.0};
  // Distance from the segment of a centre that belongs to it behind the line, per unit depth
  // (1 / cos of the bisector's angle to the normal; 1 with perpendicular ends). For listing.
  double behind_reach = 1.0;
  bool bed = false;
  bool active = true;  // a removed wall (the released gate) stays listed so indices are stable
  int wall = 0;  // index of the WallDef it came from

  bool one_sided() const { return inside.x() != 0.0 || inside.y() != 0.0; }
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

// Squared distance from p to the segment including both ends (geometry, ignores caps and
// sides), and the distance.
inline double squared_distance_to(const Segment& s, const Eigen::Vector2d& p) {
  const Eigen::Vector2d ab = s.b - s.a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - s.a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (s.a + t * ab - p).squaredNorm();
}
inline double distance_to(const Segment& s, const Eigen::Vector2d& p) {
  return std::sqrt(squared_distance_to(s, p));
}

// How a segment meets a disc centre: the contact normal (unit, from the centre towards the
// wall), the gap from the centre to the wall's surface along it (overlap = r - gap; negative
// behind a one-sided wall's line), and whether the segment acts there at all.
struct WallTouch {
  Eigen::Vector2d normal{0.0, 0.0};
  double gap = 0;
  bool acts = false;
};

// How far behind a one-sided wall's line the centre of a disc of this radius is still pushed
// back: one diameter (an overlap of 3 r, far past anything the overlap guard lets an impact do).
inline double behind_depth(double radius) { return 2.0 * radius; }
// The overlap at which a disc would be through the wall: its centre behind a one-sided face's
// reach, or on a two-sided plate's far side (the overlap guard's scale, world.hpp).
inline double pass_through_overlap(const Segment& s, double radius) {
  return radius + (s.one_sided() ? behind_depth(radius) : 0.0);
}

inline WallTouch wall_touch(const Segment& s, const Eigen::Vector2d& p, double radius) {
  auto end_point = [&](const Eigen::Vector2d& end, bool cap) {
    const Eigen::Vector2d d = end - p;
    const double dist = d.norm();
    return WallTouch{dist > 0 ? Eigen::Vector2d(d / dist) : Eigen::Vector2d(0.0, 0.0), dist, cap};
  };
  if (!s.one_sided()) {
    const SegmentProjection proj = project(s, p);
    return end_point(proj.point, !proj.at_free_end);
  }
  const Eigen::Vector2d ab = s.b - s.a;
  const double t = (p - s.a).dot(ab) / ab.squaredNorm();
  const double signed_distance = (p - s.a).dot(s.inside);  // > 0 on the discs' side
  const bool behind = signed_distance < 0;
  const bool in_span = behind ? (p - s.a).dot(s.behind_a) >= 0 && (p - s.b).dot(s.behind_b) >= 0
                              : t >= 0 && t <= 1;
  if (in_span) return {-s.inside, signed_distance, signed_distance > -behind_depth(radius)};
  if (t < 0) return end_point(s.a, s.cap_a);
  if (t > 1) return end_point(s.b, s.cap_b);
  return {};  // behind, in the part of the outside a neighbouring face owns
}

// Whether the neighbour list must hold (disc, segment): some contact can form before the disc
// has moved by the skin less twice its growth (SPEC §5; World::step).
inline bool wall_candidate(const Segment& s, const Eigen::Vector2d& p, double radius, double skin) {
  // Squared distances: the search asks this of every disc and segment at each rebuild.
  const double distance2 = squared_distance_to(s, p);
  const double front = radius + skin;
  if (distance2 < front * front) return true;
  if (!s.one_sided() || (p - s.a).dot(s.inside) >= 0) return false;
  const double behind = s.behind_reach * (behind_depth(radius) + skin);
  return distance2 < behind * behind;
}

// Splits wall polylines into segments: sides, point-contact ends and the shares of the outside
// at corners, including corners where two walls' end points meet.
std::vector<Segment> make_segments(const std::vector<WallDef>& walls);

}  // namespace runout

#include "runout/walls.hpp"

#include <cmath>

namespace runout {

namespace {

Eigen::Vector2d left_of(const Eigen::Vector2d& u) { return {-u.y(), u.x()}; }

// One end of a one-sided segment: the vertex and the unit direction from it into the segment.
struct End {
  std::size_t segment;
  bool is_a;
  Eigen::Vector2d vertex, into;
};

End end_of(const std::vector<Segment>& s, std::size_t k, bool is_a) {
  const Eigen::Vector2d u = (s[k].b - s[k].a).normalized();
  return {k, is_a, is_a ? s[k].a : s[k].b, is_a ? u : Eigen::Vector2d(-u)};
}

// Shapes one end of segment `here.segment` where it meets `other` (an end of another one-sided
// segment at the same vertex): concave corners get no point contact and share the outside
// along the bisector; a convex corner is one point contact, owned by the lower index.
void join(std::vector<Segment>& segments, const End& here, const End& other) {
  Segment& s = segments[here.segment];
  const Eigen::Vector2d n_here = s.inside, n_other = segments[other.segment].inside;
  const bool concave = other.into.dot(n_here) > -1e-12;  // the other face turns towards the discs
  bool& cap = here.is_a ? s.cap_a : s.cap_b;
  if (!concave) {
    cap = here.segment < other.segment;
    return;
  }
  cap = false;
  const Eigen::Vector2d sum = n_here + n_other;
  if (sum.norm() < 1e-12) return;  // walls folded back on each other: keep perpendicular ends
  const Eigen::Vector2d outward = -sum.normalized();  // the outside bisector
  Eigen::Vector2d split = left_of(outward);
  if (split.dot(here.into) < 0) split = -split;
  (here.is_a ? s.behind_a : s.behind_b) = split;
  s.behind_reach = std::max(s.behind_reach, 1.0 / std::max(outward.dot(-n_here), 1e-3));
}

}  // namespace

std::vector<Segment> make_segments(const std::vector<WallDef>& walls) {
  std::vector<Segment> out;
  double scale = 1.0;
  for (std::size_t w = 0; w < walls.size(); ++w) {
    const auto& pts = walls[w].points;
    for (const auto& [x, y] : pts) scale = std::max({scale, std::abs(x), std::abs(y)});
    for (std::size_t k = 0; k + 1 < pts.size(); ++k) {
      Segment s;
      s.a = {pts[k].first, pts[k].second};
      s.b = {pts[k + 1].first, pts[k + 1].second};
      s.bed = walls[w].bed;
      s.wall = static_cast<int>(w);
      const Eigen::Vector2d u = (s.b - s.a).normalized();
      if (walls[w].inside == WallInside::both) {
        s.cap_a = (k == 0);  // an inner vertex is owned by the segment before it
      } else {
        s.inside = walls[w].inside == WallInside::left ? left_of(u) : Eigen::Vector2d(-left_of(u));
        s.behind_a = u;
        s.behind_b = -u;
      }
      out.push_back(s);
    }
  }
  // Corners of one-sided walls: consecutive segments of a polyline, and end points of
  // different walls that coincide (the thesis's back wall stands on the incline's first point).
  const double tol = 1e-9 * scale;
  std::vector<End> ends;
  for (std::size_t k = 0; k < out.size(); ++k)
    if (out[k].one_sided()) { ends.push_back(end_of(out, k, true)); ends.push_back(end_of(out, k, false)); }
  for (const End& here : ends) {
    const End* partner = nullptr;
    for (const End& other : ends)
      if (other.segment != here.segment && (other.vertex - here.vertex).norm() <= tol) {
        partner = &other;
        break;
      }
    if (partner) {
      join(out, here, *partner);
      continue;
    }
    // An end standing on another one-sided face (a T, like the gate's foot on the incline) is
    // hidden: no point contact there.
    for (std::size_t k = 0; k < out.size(); ++k)
      if (k != here.segment && out[k].one_sided() && distance_to(out[k], here.vertex) <= tol)
        (here.is_a ? out[here.segment].cap_a : out[here.segment].cap_b) = false;
  }
  return out;
}

}  // namespace runout

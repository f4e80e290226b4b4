#include "runout/walls.hpp"

namespace runout {

std::vector<Segment> make_segments(const std::vector<WallDef>& walls) {
  std::vector<Segment> out;
  for (size_t w = 0; w < walls.size(); ++w) {
    const auto& pts = walls[w].points;
    for (size_t k = 0; k + 1 < pts.size(); ++k) {
      Segment s;
      s.a = {pts[k].first, pts[k].second};
      s.b = {pts[k + 1].first, pts[k + 1].second};
      s.cap_a = (k == 0);  // an inner vertex is owned by the segment before it
      s.cap_b = true;
      s.bed = walls[w].bed;
      s.wall = static_cast<int>(w);
      out.push_back(s);
    }
  }
  return out;
}

}  // namespace runout

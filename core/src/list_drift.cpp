#include "runout/list_drift.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace runout {

void ListDrift::rebuilt(double largest_radius, double skin) {
  reach_ = 2 * largest_radius + kFarSkins * skin;
  far_slack_ = (kFarSkins - 1) * skin;
  skin_ = skin;
  found_ = false;
}

void ListDrift::find_groups(const HotArray<double>& x0, const HotArray<double>& y0,
                            const std::vector<double>& wall_margin) {
  const std::size_t n = x0.size(), groups = (n + kGroup - 1) / kGroup;
  for (auto& box : box_) box.resize(4 * groups);
  wall_slack_.resize(groups);
  // Each group's box of centres at the rebuild, then the groups near it by a sweep along x.
  for (std::size_t g = 0; g < groups; ++g) {
    constexpr double inf = std::numeric_limits<double>::infinity();
    double x_lo = inf, x_hi = -inf, y_lo = inf, y_hi = -inf, margin = inf;
    const std::size_t end = std::min(n, (g + 1) * kGroup);
#pragma omp simd reduction(min : x_lo, y_lo, margin) reduction(max : x_hi, y_hi)
    for (std::size_t k = g * kGroup; k < end; ++k) {
      x_lo = std::min(x_lo, x0[k]); x_hi = std::max(x_hi, x0[k]);
      y_lo = std::min(y_lo, y0[k]); y_hi = std::max(y_hi, y0[k]);
      margin = std::min(margin, wall_margin[k]);
    }
    box_[0][4 * g] = x_lo; box_[0][4 * g + 1] = x_hi; box_[0][4 * g + 2] = y_lo; box_[0][4 * g + 3] = y_hi;
    wall_slack_[g] = margin - skin_;
  }
  const double* b = box_[0].data();
  by_x_.resize(groups);
  std::iota(by_x_.begin(), by_x_.end(), 0);
  std::sort(by_x_.begin(), by_x_.end(), [&](std::int32_t u, std::int32_t v) { return b[4 * u] < b[4 * v]; });
  near_.clear();
  for (std::size_t s = 0; s < groups; ++s) {
    const std::int32_t a = by_x_[s];
    for (std::size_t t = s + 1; t < groups && b[4 * by_x_[t]] < b[4 * a + 1] + reach_; ++t) {
      const std::int32_t c = by_x_[t];
      const double gx = std::max(0.0, b[4 * c] - b[4 * a + 1]);
      const double gy = std::max({0.0, b[4 * c + 2] - b[4 * a + 3], b[4 * a + 2] - b[4 * c + 3]});
      if (gx * gx + gy * gy < reach_ * reach_) near_.push_back({a, c});
    }
  }
  found_ = true;
  split_bounds_.clear();
}

void ListDrift::split(const std::vector<std::int64_t>& bounds) {
  if (bounds == split_bounds_) return;
  split_bounds_ = bounds;
  const std::size_t blocks = bounds.size() - 1;
  auto block_of = [&](std::int32_t g) {
    const auto first_disc = static_cast<std::int64_t>(g) * static_cast<std::int64_t>(kGroup);
    return static_cast<std::size_t>(std::upper_bound(bounds.begin() + 1, bounds.end() - 1, first_disc) - bounds.begin() - 1);
  };
  // A stable counting sort by block, the pairs across blocks last.
  inside_start_.assign(blocks + 2, 0);
  std::vector<std::size_t> where(near_.size());
  for (std::size_t q = 0; q < near_.size(); ++q) {
    const std::size_t a = block_of(near_[q].first), c = block_of(near_[q].second);
    where[q] = a == c ? a : blocks;
    ++inside_start_[where[q] + 1];
  }
  std::partial_sum(inside_start_.begin(), inside_start_.end(), inside_start_.begin());
  by_block_.resize(near_.size());
  std::vector<std::size_t> next(inside_start_.begin(), inside_start_.end() - 1);
  for (std::size_t q = 0; q < near_.size(); ++q) by_block_[next[where[q]]++] = near_[q];
}

ListDrift::Partial ListDrift::measure(const HotArray<double>& x, const HotArray<double>& y,
                                      const HotArray<double>& x0, const HotArray<double>& y0,
                                      int block, int slot) {
  const auto lo = static_cast<std::size_t>(split_bounds_[block]);
  const auto hi = static_cast<std::size_t>(split_bounds_[block + 1]);
  const double* __restrict xs = x.data();
  const double* __restrict ys = y.data();
  const double* __restrict xs0 = x0.data();
  const double* __restrict ys0 = y0.data();
  double* __restrict box = box_[slot].data();
  Partial part;
  for (std::size_t g = lo / kGroup; g * kGroup < hi; ++g) {
    constexpr double inf = std::numeric_limits<double>::infinity();
    double ux_lo = inf, ux_hi = -inf, uy_lo = inf, uy_hi = -inf, u2 = 0;
    const std::size_t end = std::min(hi, (g + 1) * kGroup);
#pragma omp simd reduction(min : ux_lo, uy_lo) reduction(max : ux_hi, uy_hi, u2)
    for (std::size_t k = g * kGroup; k < end; ++k) {
      const double ux = xs[k] - xs0[k], uy = ys[k] - ys0[k];
      ux_lo = std::min(ux_lo, ux); ux_hi = std::max(ux_hi, ux);
      uy_lo = std::min(uy_lo, uy); uy_hi = std::max(uy_hi, uy);
      u2 = std::max(u2, ux * ux + uy * uy);
    }
    box[4 * g] = ux_lo; box[4 * g + 1] = ux_hi; box[4 * g + 2] = uy_lo; box[4 * g + 3] = uy_hi;
    const double dx = ux_hi - ux_lo, dy = uy_hi - uy_lo;
    part.pairs2 = std::max(part.pairs2, dx * dx + dy * dy);
    part.walls = std::max(part.walls, std::sqrt(u2) - wall_slack_[g]);
  }
  part.pairs2 = std::max(part.pairs2, pairs2_of(inside_start_[block], inside_start_[block + 1], slot));
  return part;
}

double ListDrift::pairs2_of(std::size_t from, std::size_t to, int slot) const {
  const double* b = box_[slot].data();
  double pairs2 = 0;
  for (std::size_t q = from; q < to; ++q) {
    const auto [a, c] = by_block_[q];
    const double dx = std::max(b[4 * a + 1], b[4 * c + 1]) - std::min(b[4 * a], b[4 * c]);
    const double dy = std::max(b[4 * a + 3], b[4 * c + 3]) - std::min(b[4 * a + 2], b[4 * c + 2]);
    pairs2 = std::max(pairs2, dx * dx + dy * dy);
  }
  return pairs2;
}

double ListDrift::closing(const HotArray<double>& x, const HotArray<double>& y,
                          const HotArray<double>& x0, const HotArray<double>& y0,
                          const std::vector<double>& wall_margin, double all_spread) {
  if (!found_) find_groups(x0, y0, wall_margin);
  split({0, static_cast<std::int64_t>(x.size())});
  return bound(all_spread, measure(x, y, x0, y0, 0, 0), 0);
}

double ListDrift::bound(double all_spread, const Partial& blocks, int slot) const {
  // A spread that is not finite (a state gone bad) must not read as fresh lists.
  if (!(all_spread <= std::numeric_limits<double>::max())) return std::numeric_limits<double>::infinity();
  const std::size_t across = inside_start_[split_bounds_.size() - 1];
  const double pairs2 = std::max(blocks.pairs2, pairs2_of(across, by_block_.size(), slot));
  return std::max({std::sqrt(pairs2), all_spread - far_slack_, blocks.walls});
}

}  // namespace runout

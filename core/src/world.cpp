// The step as a list of named, timed phases (SPEC §2), the neighbour lists and the spatial
// reordering. The threads' forces and motion: parallel_step.cpp; the phases themselves:
// contact_forces.cpp, integrate.cpp; checks: safety.cpp.
#include "runout/world.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <tuple>

#include "step_phases.hpp"

namespace runout {

World::World(Particles particles, std::vector<Segment> segments, ContactTable table,
             StepSettings settings)
    : particles_(std::move(particles)), segments_(std::move(segments)),
      table_(std::move(table)), settings_(settings) {
  settings_.threads = std::clamp(settings_.threads, 1, kMaxThreads);
  settings_.contact.frictional = table_.frictional();
  dispatch(settings_.contact, [&](auto model) {
    using Model = decltype(model);
    history_width_ = Model::kHistory;
    normal_history_width_ = Model::NormalLaw::kHistory;
  });
  laws_ = phases::derive_laws(settings_.contact, table_);
}

void World::forget_normal_history() {
  // The normal law's columns come first (contact.hpp).
  auto forget = [&](HotArray<double>& history, std::size_t count) {
    std::fill_n(history.begin(), std::min(history.size(), normal_history_width_ * count), 0.0);
  };
  forget(pairs_.history, pairs_.size());
  forget(wall_contacts_.history, wall_contacts_.size());
}

void World::deactivate_wall(int wall_index) {
  for (auto& s : segments_)
    if (s.wall == wall_index) s.active = false;
  lists_valid_ = false;
}

void World::deactivate_wall_segment(std::size_t segment) {
  segments_.at(segment).active = false;
  lists_valid_ = false;
}

void World::resize_disc(std::size_t k, double radius, double mass, double inertia) {
  auto& p = particles_;
  p.radius[k] = radius;
  p.mass[k] = mass;
  p.inv_mass[k] = 1.0 / mass;
  p.inv_inertia[k] = 1.0 / inertia;
  if (lists_valid_) max_growth_ = std::max(max_growth_, radius - radius_at_rebuild_[k]);
}

void World::restore_history(const PairContacts& pairs, const WallContacts& walls) {
  pairs_ = pairs;
  wall_contacts_ = walls;
  // The search keeps the history of (i, j) keys present in the lists it replaces.
  rebuild_lists();
}

// Renumbers the discs along x (in strips a hundredth of a large radius wide, then by y), so each
// thread's contiguous block of discs is a stretch of the flow cut from the next by a straight
// line across it: its neighbours mostly live in the same block (and cache), and the fewest pairs
// and cache lines cross between the threads each step (columns one large diameter wide cut
// part-way up a column, with twice the crossing lines; docs/performance_log.md, issue 11
// twenty-ninth and thirty-fourth sessions). Contact history follows the discs. Done on a fixed
// step cadence, so results stay bit-identical across thread counts and skins.
void World::reorder_discs() {
  auto& p = particles_;
  const std::size_t n = p.size();
  if (n < 2) return;
  double xmin = p.x[0], xmax = p.x[0], ymin = p.y[0], ymax = p.y[0], rmax = 0;
  for (std::size_t k = 0; k < n; ++k) {
    xmin = std::min(xmin, p.x[k]); xmax = std::max(xmax, p.x[k]);
    ymin = std::min(ymin, p.y[k]); ymax = std::max(ymax, p.y[k]);
    rmax = std::max(rmax, p.radius[k]);
  }
  // Wider strips only where the discs span more than 2^30 of them (explicit discs may lie up to
  // 2e9 m apart), so each strip and row index stays below 2^30 and the packed key below 2^62.
  const double span = std::max(xmax - xmin, ymax - ymin);
  const double cell = std::max({0.01 * rmax, span / static_cast<double>(1 << 30), 1e-12});
  std::vector<std::pair<std::int64_t, std::int64_t>> key(n);
  for (std::size_t k = 0; k < n; ++k) {
    const auto cx = static_cast<std::int64_t>((p.x[k] - xmin) / cell);
    const auto cy = static_cast<std::int64_t>((p.y[k] - ymin) / cell);
    key[k] = {cx * (std::int64_t(1) << 31) + cy, static_cast<std::int64_t>(k)};
  }
  std::sort(key.begin(), key.end());
  std::vector<std::int32_t> new_index(n);
  for (std::size_t k = 0; k < n; ++k) new_index[key[k].second] = static_cast<std::int32_t>(k);
  auto permute = [&](auto& v) {
    auto copy = v;
    for (std::size_t k = 0; k < n; ++k) v[k] = copy[key[k].second];
  };
  Particles::for_each_array(p, [&](const char*, auto& v) { permute(v); });

  // History keyed by the new numbering, rows sorted, ready for the search to carry over.
  // Contacts with all-zero history (not touching) need not be carried.
  const int W = history_width_;
  auto carried = [W](const HotArray<double>& h, std::size_t count, std::size_t q) {
    for (int m = 0; m < W; ++m) if (h[m * count + q] != 0.0) return true;
    return false;
  };
  auto rows_of = [&](std::vector<std::pair<std::pair<std::int32_t, std::int32_t>, std::size_t>>& keys,
                     const HotArray<double>& history, HotArray<std::int32_t>& row_start,
                     HotArray<std::int32_t>& second, HotArray<double>& out) {
    std::sort(keys.begin(), keys.end());
    row_start.assign(n + 1, 0);
    const std::size_t count = W > 0 ? history.size() / W : 0, kept = keys.size();
    out.assign(kept * W, 0.0);
    for (std::size_t e = 0; e < kept; ++e) {
      const auto& [key, q] = keys[e];
      ++row_start[key.first + 1];
      second.push_back(key.second);
      for (int m = 0; m < W; ++m) out[m * kept + e] = history[m * count + q];
    }
    for (std::size_t k = 0; k < n; ++k) row_start[k + 1] += row_start[k];
  };
  std::vector<std::pair<std::pair<std::int32_t, std::int32_t>, std::size_t>> keys;
  for (std::size_t q = 0; q < pairs_.size(); ++q) {
    if (!carried(pairs_.history, pairs_.size(), q)) continue;
    std::int32_t a = new_index[pairs_.i[q]], b = new_index[pairs_.j[q]];
    if (a > b) std::swap(a, b);
    keys.push_back({{a, b}, q});
  }
  PairContacts old;
  old.history_width = W;
  rows_of(keys, pairs_.history, old.row_start, old.j, old.history);
  keys.clear();
  for (std::size_t q = 0; q < wall_contacts_.size(); ++q)
    keys.push_back({{new_index[wall_contacts_.disc[q]], wall_contacts_.segment[q]}, q});
  WallContacts old_walls;
  old_walls.history_width = W;
  rows_of(keys, wall_contacts_.history, old_walls.row_start, old_walls.segment, old_walls.history);
  restore_history(old, old_walls);
}

void World::rebuild_lists() {
  const auto t0 = Clock::now();
  search_.rebuild(particles_, segments_, settings_.skin, settings_.threads, blocks_.bounds(),
                  history_width_, pairs_, wall_contacts_, runs_);
  // In parallel, each thread writing the share its block's step will read (its block's discs
  // and their rows, as the search did): one thread wrote them all in ~13 us, and the others
  // then took those lines back in their first step.
  const auto& p = particles_;
  const auto n = static_cast<std::int64_t>(p.size());
  pairs_.kind.resize(pairs_.size());
  x_at_rebuild_.resize(p.size());
  y_at_rebuild_.resize(p.size());
  radius_at_rebuild_.resize(p.size());
  const std::vector<std::int64_t>& b = blocks_.bounds();
#pragma omp parallel num_threads(settings_.threads)
  {
    const int t = omp_get_thread_num(), T = omp_get_num_threads();
    const auto [lo, hi] = team_block(b, n, t, T);
    for (std::int64_t q = pairs_.row_start[lo]; q < pairs_.row_start[hi]; ++q)
      pairs_.kind[q] = p.species[pairs_.i[q]] * table_.species_count + p.species[pairs_.j[q]];
    for (std::int64_t k = lo; k < hi; ++k) {
      x_at_rebuild_[k] = p.x[k];
      y_at_rebuild_[k] = p.y[k];
      radius_at_rebuild_[k] = p.radius[k];
    }
  }
  drift_.rebuilt(search_.largest_radius(), settings_.skin);
  recent_count_ = 0;
  list_drift_ = 0;
  watch_groups_ = false;
  max_growth_ = 0;
  lists_valid_ = true;
  ++lists_version_;
  profile_.rebuild += seconds_since(t0);
  ++profile_.rebuilds;
}

// Symplectic Euler (the seed's, eqs. 2.15–2.18): [rebuild] forces, kick dt, drift dt.
// Velocity Verlet: kick dt/2 + drift dt, [rebuild] forces, kick dt/2.
void World::advance(std::int64_t steps) {
  // The lists hold every pair and disc–wall pair within the skin at the rebuild (SPEC §5). An
  // unlisted pair can touch only once the two have come closer by the skin less their growth:
  // list_drift bounds how much closer any two discs, or a disc and a fixed wall, have come
  // (the spread of the displacements, not twice the largest: a flow moving as one barely
  // stales its lists), and a radius grows on both sides of a pair, and by 2 r behind a wall.
  const double dt = settings_.dt;
  auto rebuild_if_moved = [&] {
    if (!lists_valid_ || list_drift_ + 2 * max_growth_ >= settings_.skin) rebuild_lists();
  };
  while (steps > 0) {
    const std::int64_t reorder = settings_.reorder_every;
    if (reorder > 0 && steps_ % reorder == 0) reorder_discs();
    std::int64_t taken = 1;
    if (settings_.integrator == IntegratorKind::symplectic_euler) {
      rebuild_if_moved();
      // Up to the next reordering (a step's own start).
      const std::int64_t before_reorder = reorder > 0 ? reorder - steps_ % reorder : steps;
      taken = forces_and_motion(true, dt, dt, std::min(steps, before_reorder));
    } else {
      if (!lists_valid_) {  // first step: accelerations at the initial state
        rebuild_lists();
        forces_and_motion(true, 0.0, 0.0, 1);
      }
      forces_and_motion(false, 0.5 * dt, dt, 1);
      rebuild_if_moved();
      forces_and_motion(true, 0.5 * dt, 0.0, 1);
    }
    for (std::int64_t s = 0; s < taken; ++s) {  // added step by step: one step's bits
      time_ += dt;
      ++steps_;
    }
    steps -= taken;
    check_finite();
  }
}

}  // namespace runout

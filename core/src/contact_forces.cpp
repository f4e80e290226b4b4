// The contact kernel (SPEC §2): one loop body for disc–disc pairs and disc–wall contacts,
// templated on the contact model (contact/registry.hpp). A source turns contact q into its
// kinematics; the model turns those and the history into forces and torques; the kernel stores
// them and books the ledger. A wall plays j with zero velocity, spin and radius.
#include <algorithm>
#include <cmath>

#include "step_phases.hpp"

namespace runout::phases {

namespace {

// One contact as its source sees it.
struct Contact {
  ContactKinematics kinematics;
  double nx = 0, ny = 0;    // unit normal from the disc towards its partner
  bool touching = false;
  std::int32_t kind = 0;    // row of the parameter table
  double guard_depth = 1;   // depth at which the contact would be passed through (world.hpp)
};

// Disc–disc pairs. Flat and branch-free so the compiler vectorises the loop: a pair that does
// not touch computes a force and then discards it, and its history is forgotten.
struct PairSource {
  static constexpr bool kPairs = true;
  const double* __restrict x; const double* __restrict y;
  const double* __restrict vx; const double* __restrict vy; const double* __restrict om;
  const double* __restrict r;
  const std::int32_t* __restrict pi; const std::int32_t* __restrict pj;
  const std::int32_t* __restrict kind;
  double dt;

  [[gnu::always_inline]] Contact operator()(std::int64_t q) const {
    const std::int32_t i = pi[q], j = pj[q];
    const double dx = x[j] - x[i], dy = y[j] - y[i];
    const double dist2 = dx * dx + dy * dy;
    const double rsum = r[i] + r[j];
    const double dist = std::sqrt(dist2);
    // Coincident centres have no normal; dx = dy = 0 gives the zero vector and a finite
    // force (eq. 2.2), without a branch.
    const double inv_dist = 1.0 / std::max(dist, 1e-300);
    Contact c;
    c.nx = dx * inv_dist;
    c.ny = dy * inv_dist;
    c.touching = dist2 < rsum * rsum;
    const double dvx = vx[j] - vx[i], dvy = vy[j] - vy[i];
    ContactKinematics& k = c.kinematics;
    k.overlap = rsum - dist;  // eq. 2.1
    k.overlap_rate = -(dvx * c.nx + dvy * c.ny);
    k.slip = -dvx * c.ny + dvy * c.nx - (om[j] * r[j] + om[i] * r[i]);  // eq. 2.7
    k.spin_difference = om[i] - om[j];
    k.radius_i = r[i];
    k.radius_j = r[j];
    k.dt = dt;
    c.kind = kind[q];
    c.guard_depth = rsum;
    return c;
  }
};

// Disc–wall contacts: few, so a plain loop (wall_touch branches on the segment's kind).
struct WallSource {
  static constexpr bool kPairs = false;
  const Particles& p;
  const std::vector<Segment>& segments;
  const std::int32_t* disc; const std::int32_t* segment;
  double dt;

  [[gnu::always_inline]] Contact operator()(std::int64_t q) const {
    const std::int32_t i = disc[q];
    const Segment& s = segments[segment[q]];
    const double r = p.radius[i];
    const WallTouch touch = wall_touch(s, {p.x[i], p.y[i]}, r);
    Contact c;
    c.nx = touch.normal.x();
    c.ny = touch.normal.y();
    c.touching = s.active && touch.acts && touch.gap < r;
    ContactKinematics& k = c.kinematics;
    k.overlap = r - touch.gap;
    k.overlap_rate = p.vx[i] * c.nx + p.vy[i] * c.ny;
    k.slip = p.vx[i] * c.ny - p.vy[i] * c.nx - p.omega[i] * r;
    k.spin_difference = p.omega[i];
    k.radius_i = r;
    k.radius_j = 0;
    k.dt = dt;
    c.kind = p.species[i];
    c.guard_depth = pass_through_overlap(s, r);
    return c;
  }
};

// What one contact adds to the pass's sums.
struct ContactSums {
  double worst = 0, loss_normal = 0, loss_friction = 0, loss_rolling = 0;
};

template <class Model, bool kLedger, class Source>
struct Kernel {
  Source source;
  typename Model::Row law;
  double impact_rate;
  // Column m of contact q at [m * count + q] (SoA): read from one buffer, written to the
  // other, or to the same one (phases::HistoryTurn; contact q's only, so `omp simd` holds).
  const double* history_in;
  double* history_out;
  std::int64_t count;
  // The push on the disc (pairs: on i) at [q]; pairs also write the push on j at [on_j + q].
  double* __restrict fx; double* __restrict fy; double* __restrict torque;
  std::int64_t on_j;

  [[gnu::always_inline]] ContactSums one(std::int64_t q) const {
    constexpr int W = Model::kHistory;
    const Contact c = source(q);
    double h[W > 0 ? W : 1];
    for (int m = 0; m < W; ++m) h[m] = history_in[m * count + q];
    ContactSums sums;
    // A contact that ends banks the loss its history committed (Walton–Braun hysteresis).
    if constexpr (kLedger) sums.loss_normal = Model::committed_loss(law, c.kind, h);
    ContactLoss loss;
    const ContactAction a = Model::evaluate(law, c.kind, c.kinematics, h, loss);
    if constexpr (kLedger) {
      sums.loss_normal = c.touching ? loss.normal : sums.loss_normal;
      sums.loss_friction = c.touching ? loss.friction : 0.0;
      sums.loss_rolling = c.touching ? loss.rolling : 0.0;
    }
    for (int m = 0; m < W; ++m) history_out[m * count + q] = c.touching ? h[m] : 0.0;
    const double fn = c.touching ? a.normal : 0.0, ft = c.touching ? a.tangential : 0.0;
    // Force on i: the normal pushes i away from j, the tangential acts along s = (-ny, nx).
    const double push_x = -fn * c.nx - ft * c.ny, push_y = -fn * c.ny + ft * c.nx;
    fx[q] = push_x;
    fy[q] = push_y;
    if constexpr (Source::kPairs) {  // Newton's third law
      fx[on_j + q] = -push_x;
      fy[on_j + q] = -push_y;
    }
    // Without friction or rolling the torques stay the zeros the list rebuild wrote.
    if constexpr (Model::kFriction || Model::kRolling) {
      torque[q] = c.touching ? a.torque_i : 0.0;
      if constexpr (Source::kPairs) torque[on_j + q] = c.touching ? a.torque_j : 0.0;
    }
    // The guard watches impacts (loading faster than impact_rate), not the permanent set of
    // a static hysteretic contact.
    // (Bitwise &: both sides are evaluated, so no load becomes conditional on the other.)
    const bool guarded = c.touching & (c.kinematics.overlap_rate > impact_rate);
    sums.worst = guarded ? c.kinematics.overlap / c.guard_depth : 0.0;
    return sums;
  }

  PassSums operator()(std::int64_t begin, std::int64_t end) const {
    // A local copy, so the compiler knows the stores below cannot move these pointers.
    const Kernel k = *this;
    double worst = 0, loss_normal = 0, loss_friction = 0, loss_rolling = 0;
    if constexpr (Source::kPairs) {
#pragma omp simd reduction(max : worst) reduction(+ : loss_normal, loss_friction, loss_rolling)
      for (std::int64_t q = begin; q < end; ++q) {
        const ContactSums s = k.one(q);
        worst = std::max(worst, s.worst);
        loss_normal += s.loss_normal; loss_friction += s.loss_friction; loss_rolling += s.loss_rolling;
      }
    } else {
      for (std::int64_t q = begin; q < end; ++q) {
        const ContactSums s = one(q);
        worst = std::max(worst, s.worst);
        loss_normal += s.loss_normal; loss_friction += s.loss_friction; loss_rolling += s.loss_rolling;
      }
    }
    return {worst, loss_normal, loss_friction, loss_rolling};
  }
};

// Runs a kernel over contacts [lo, hi) of `count`, whose ends are ends of blocks of `block`.
// With the ledger, each block's sums go to blocks[b] and are added in block order, each thread
// carrying the sum on over its own blocks (LedgerBlocks::carry), so they are the same bits
// whatever the thread count and however the blocks are shared (a resumed run may use another
// count, SPEC §8).
template <class Kernel>
PassSums run_blocks(const Kernel& kernel, std::int64_t lo, std::int64_t hi, bool ledger,
                    LedgerBlocks::Block* blocks, std::int64_t block) {
  if (!ledger) return kernel(lo, hi);
  PassSums worst;
  // An empty range may start at the contact count, inside the last block: that block is
  // another thread's.
  if (lo >= hi) return worst;
  for (std::int64_t b = lo / block; b * block < hi; ++b) {
    blocks[b].sums = kernel(b * block, std::min(hi, (b + 1) * block));
    worst.worst = std::max(worst.worst, blocks[b].sums.worst);
  }
  return worst;
}

PairSource pair_source(const StepContext& step, const Particles& p, const PairContacts& c) {
  return {p.x.data(), p.y.data(), p.vx.data(), p.vy.data(), p.omega.data(), p.radius.data(),
          c.i.data(), c.j.data(), c.kind.data(), step.settings.dt};
}
WallSource wall_source(const StepContext& step, const Particles& p, const WallContacts& c) {
  return {p, step.segments, c.disc.data(), c.segment.data(), step.settings.dt};
}

// The World's tables of the model's laws (derive_laws made them for this Model).
template <class Model>
const typename Model::Tables& tables_of(const std::shared_ptr<const void>& derived) {
  return *static_cast<const typename Model::Tables*>(derived.get());
}

template <class Model, bool kLedger>
PassSums forces_with(const StepContext& step, const Particles& p, PairContacts& pairs,
                     WallContacts& walls, const ContactRange& range, LedgerBlocks& ledger,
                     const HistoryTurn& history) {
  const StepSettings& st = step.settings;
  const auto& pair_law = tables_of<Model>(step.laws.pairs);
  const Kernel<Model, kLedger, PairSource> pk{pair_source(step, p, pairs), Model::row(pair_law),
                                              st.impact_rate, history.pairs_in, history.pairs_out,
                                              static_cast<std::int64_t>(pairs.size()),
                                              pairs.fx.data(), pairs.fy.data(),
                                              pairs.torque.data(),
                                              static_cast<std::int64_t>(pairs.j_offset())};
  const auto& wall_law = tables_of<Model>(step.laws.walls);
  const Kernel<Model, kLedger, WallSource> wk{wall_source(step, p, walls), Model::row(wall_law),
                                              st.impact_rate, history.walls_in, history.walls_out,
                                              static_cast<std::int64_t>(walls.size()),
                                              walls.fx.data(), walls.fy.data(),
                                              walls.torque.data(), 0};
  const PassSums a = run_blocks(pk, range.pair_lo, range.pair_hi, kLedger, ledger.pairs.data(),
                                kPairLedgerBlock);
  const PassSums b = run_blocks(wk, range.wall_lo, range.wall_hi, kLedger, ledger.walls.data(),
                                kWallLedgerBlock);
  return a + b;
}

template <class Model, class Source, class Out>
void energy_of(const Source& source, const typename Model::Tables& tables,
               const HotArray<double>& history, std::int64_t n, Out& e) {
  constexpr int W = Model::kHistory;
  const auto law = Model::row(tables);
  for (std::int64_t q = 0; q < n; ++q) {
    const Contact c = source(q);
    if (!c.touching) continue;
    double h[W > 0 ? W : 1];
    for (int m = 0; m < W; ++m) h[m] = history[m * n + q];
    e.elastic += Model::elastic_energy(law, c.kind, c.kinematics, h);
    e.committed_normal += Model::committed_loss(law, c.kind, h);
  }
}

}  // namespace

ContactRange contact_range(const PairContacts& pairs, const WallContacts& walls,
                           std::int64_t disc_lo, std::int64_t disc_hi, std::int64_t n,
                           ContactGrain grain) {
  // The contacts of the block's rows, both ends moved to the grain's next end: the ends of
  // consecutive disc blocks meet, so every contact is taken once.
  auto at = [&](const HotArray<std::int32_t>& row_start, std::int64_t disc, std::int64_t count,
                std::int64_t block) {
    if (disc >= n) return count;
    const std::int64_t q = row_start.empty() ? 0 : row_start[disc];
    return std::min(count, (q + block - 1) / block * block);
  };
  const auto np = static_cast<std::int64_t>(pairs.size()), nw = static_cast<std::int64_t>(walls.size());
  return {at(pairs.row_start, disc_lo, np, grain.pairs),
          at(pairs.row_start, disc_hi, np, grain.pairs),
          at(walls.row_start, disc_lo, nw, grain.walls),
          at(walls.row_start, disc_hi, nw, grain.walls)};
}

LawTables derive_laws(const ContactChoice& contact, const ContactTable& table) {
  LawTables laws;
  dispatch(contact, [&](auto model) {
    using Model = decltype(model);
    laws.pairs = std::make_shared<const typename Model::Tables>(Model::tables(table.pair));
    laws.walls = std::make_shared<const typename Model::Tables>(Model::tables(table.wall));
  });
  return laws;
}

PassSums contact_forces(const StepContext& step, const Particles& p, PairContacts& pairs,
                        WallContacts& walls, const ContactRange& range, LedgerBlocks& ledger,
                        const HistoryTurn& history) {
  PassSums sums;
  dispatch(step.settings.contact, [&](auto model) {
    using Model = decltype(model);
    sums = step.settings.track_energy
               ? forces_with<Model, true>(step, p, pairs, walls, range, ledger, history)
               : forces_with<Model, false>(step, p, pairs, walls, range, ledger, history);
  });
  return sums;
}

ContactEnergy contact_energy(const StepContext& step, const Particles& p,
                             const PairContacts& pairs, const WallContacts& walls) {
  ContactEnergy e;
  dispatch(step.settings.contact, [&](auto model) {
    using Model = decltype(model);
    energy_of<Model>(pair_source(step, p, pairs), tables_of<Model>(step.laws.pairs),
                     pairs.history, static_cast<std::int64_t>(pairs.size()), e);
    energy_of<Model>(wall_source(step, p, walls), tables_of<Model>(step.laws.walls),
                     walls.history, static_cast<std::int64_t>(walls.size()), e);
  });
  return e;
}

}  // namespace runout::phases

namespace runout {

void LedgerBlocks::size_for(const PairContacts& pairs, const WallContacts& walls) {
  auto blocks = [](std::size_t count, std::int64_t block) { return (count + block - 1) / block; };
  this->pairs.resize(blocks(pairs.size(), kPairLedgerBlock));
  this->walls.resize(blocks(walls.size(), kWallLedgerBlock));
}

LedgerBlocks::Partial LedgerBlocks::carry(Partial from, const ContactRange& range) const {
  // An empty range may start inside the last block, which is then another thread's.
  auto add = [](PassSums t, const std::vector<Block>& blocks, std::int64_t lo, std::int64_t hi,
                std::int64_t block) {
    if (lo >= hi) return t;
    for (std::int64_t b = lo / block; b * block < hi; ++b) t = t + blocks[b].sums;
    return t;
  };
  from.pairs = add(from.pairs, pairs, range.pair_lo, range.pair_hi, kPairLedgerBlock);
  from.walls = add(from.walls, walls, range.wall_lo, range.wall_hi, kWallLedgerBlock);
  return from;
}

}  // namespace runout

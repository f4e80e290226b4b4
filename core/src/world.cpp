#include "runout/world.hpp"

#include <omp.h>

#include <chrono>
#include <tuple>
#include <cmath>
#include <sstream>

#include "runout/errors.hpp"

namespace runout {

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Per-law coefficient lookup, so the pair loop below stays one piece of code.
template <class Law> typename Law::Coefficients normal_coefficients(const PairCoefficients& c);
template <> WaltonBraun::Coefficients normal_coefficients<WaltonBraun>(const PairCoefficients& c) {
  return c.walton_braun;
}
template <>
LinearDashpot::Coefficients normal_coefficients<LinearDashpot>(const PairCoefficients& c) {
  return c.linear_dashpot;
}
template <> Hertz::Coefficients normal_coefficients<Hertz>(const PairCoefficients& c) {
  return c.hertz;
}

}  // namespace

World::World(Particles particles, std::vector<Segment> segments, ContactTable table,
             StepSettings settings)
    : particles_(std::move(particles)), segments_(std::move(segments)),
      table_(std::move(table)), settings_(settings), frictional_(table_.frictional()) {
  settings_.threads = std::clamp(settings_.threads, 1, kMaxThreads);
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

// Renumbers the discs along x (then y) in cells of about one large diameter, so each thread's
// contiguous block of discs is a compact stretch of the flow and its neighbours mostly live in
// the same block (and cache). Contact history follows the discs. Done on a fixed step cadence,
// so results stay bit-identical across thread counts and skins.
void World::reorder_discs() {
  auto& p = particles_;
  const std::size_t n = p.size();
  if (n < 2) return;
  double xmin = p.x[0], ymin = p.y[0], rmax = 0;
  for (std::size_t k = 0; k < n; ++k) {
    xmin = std::min(xmin, p.x[k]); ymin = std::min(ymin, p.y[k]); rmax = std::max(rmax, p.radius[k]);
  }
  const double cell = std::max(2.0 * rmax, 1e-12);
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
  permute(p.x); permute(p.y); permute(p.vx); permute(p.vy); permute(p.omega);
  permute(p.radius); permute(p.inv_mass); permute(p.inv_inertia); permute(p.species);
  permute(p.ax); permute(p.ay); permute(p.alpha); permute(p.angle); permute(p.mass); permute(p.id);

  // History keyed by the new numbering, rows sorted, ready for the search to carry over.
  PairContacts old;
  std::vector<std::tuple<std::int32_t, std::int32_t, double, double>> pairs;
  auto spring_of = [](const auto& contacts, std::size_t q) {
    return contacts.tangential_spring.empty() ? 0.0 : contacts.tangential_spring[q];
  };
  for (std::size_t q = 0; q < pairs_.size(); ++q) {
    if (pairs_.overlap_max[q] == 0.0 && spring_of(pairs_, q) == 0.0) continue;
    std::int32_t a = new_index[pairs_.i[q]], b = new_index[pairs_.j[q]];
    if (a > b) std::swap(a, b);
    pairs.emplace_back(a, b, pairs_.overlap_max[q], spring_of(pairs_, q));
  }
  std::sort(pairs.begin(), pairs.end());
  old.row_start.assign(n + 1, 0);
  for (const auto& [a, b, om, sp] : pairs) {
    ++old.row_start[a + 1];
    old.j.push_back(b); old.overlap_max.push_back(om);
    if (frictional_) old.tangential_spring.push_back(sp);
  }
  for (std::size_t k = 0; k < n; ++k) old.row_start[k + 1] += old.row_start[k];
  WallContacts old_walls;
  std::vector<std::tuple<std::int32_t, std::int32_t, double, double>> walls;
  for (std::size_t q = 0; q < wall_contacts_.size(); ++q)
    walls.emplace_back(new_index[wall_contacts_.disc[q]], wall_contacts_.segment[q],
                       wall_contacts_.overlap_max[q], spring_of(wall_contacts_, q));
  std::sort(walls.begin(), walls.end());
  old_walls.row_start.assign(n + 1, 0);
  for (const auto& [a, seg, om, sp] : walls) {
    ++old_walls.row_start[a + 1];
    old_walls.segment.push_back(seg); old_walls.overlap_max.push_back(om);
    if (frictional_) old_walls.tangential_spring.push_back(sp);
  }
  for (std::size_t k = 0; k < n; ++k) old_walls.row_start[k + 1] += old_walls.row_start[k];
  restore_history(old, old_walls);
}

void World::rebuild_lists() {
  const auto t0 = Clock::now();
  search_.rebuild(particles_, segments_, settings_.skin, settings_.threads, frictional_, pairs_,
                  wall_contacts_);
  x_at_rebuild_ = particles_.x;
  y_at_rebuild_ = particles_.y;
  radius_at_rebuild_ = particles_.radius;
  max_displacement2_ = 0;
  max_growth_ = 0;
  lists_valid_ = true;
  profile_.rebuild += seconds_since(t0);
  ++profile_.rebuilds;
}

// The one disc–disc pair loop (SPEC §2). Flat and branch-free over the candidate pairs so the
// compiler vectorises it: a pair that does not touch computes a force and then discards it,
// and its history is forgotten (the contact has broken). Raw pointers and per-pair-type
// coefficient arrays keep every load a plain (gathered) double.
namespace {

// kFriction false (mu = 0 everywhere): no slip, no tangential spring read or written, and the
// per-pair tangential force stays the zero the list rebuild wrote.
template <class Law, bool kLedger, bool kFriction>
struct PairKernel {
  const double* x; const double* y; const double* vx; const double* vy; const double* om;
  const double* r; const std::int32_t* species; const std::int32_t* pi; const std::int32_t* pj;
  const typename Law::Coefficients* normal; const CundallStrack* tangential;
  int species_count;
  double dt;
  double impact_rate;
  double* overlap_max; double* spring; double* fx; double* fy; double* ft;

  PassSums operator()(std::int64_t begin, std::int64_t end) const {
    // Locals, so the compiler knows the stores below cannot move these pointers.
    const double* __restrict x = this->x; const double* __restrict y = this->y;
    const double* __restrict vx = this->vx; const double* __restrict vy = this->vy;
    const double* __restrict om = this->om; const double* __restrict r = this->r;
    const std::int32_t* __restrict species = this->species;
    const std::int32_t* __restrict pi = this->pi; const std::int32_t* __restrict pj = this->pj;
    const typename Law::Coefficients* __restrict normal = this->normal;
    const CundallStrack* __restrict tangential = this->tangential;
    double* __restrict overlap_max = this->overlap_max; double* __restrict spring = this->spring;
    double* __restrict fx = this->fx; double* __restrict fy = this->fy; double* __restrict ft = this->ft;
    const int species_count = this->species_count;
    const double dt = this->dt, impact_rate = this->impact_rate;
    double worst = 0, loss_normal = 0, loss_friction = 0;
#pragma omp simd reduction(max : worst) reduction(+ : loss_normal, loss_friction)
    for (std::int64_t q = begin; q < end; ++q) {
      const std::int32_t i = pi[q], j = pj[q];
      const double dx = x[j] - x[i], dy = y[j] - y[i];
      const double dist2 = dx * dx + dy * dy;
      const double rsum = r[i] + r[j];
      const bool touching = dist2 < rsum * rsum;
      const double dist = std::sqrt(dist2);
      // Coincident centres have no normal; dx = dy = 0 gives the zero vector and a finite
      // force (eq. 2.2). Branch-free, so the loop vectorises.
      const double inv_dist = 1.0 / std::max(dist, 1e-300);
      const double nx = dx * inv_dist, ny = dy * inv_dist;
      const double overlap = rsum - dist;  // eq. 2.1
      const double dvx = vx[j] - vx[i], dvy = vy[j] - vy[i];
      const double overlap_rate = -(dvx * nx + dvy * ny);
      // Without friction (kFriction false) the slip, the spring and F_t are never loaded,
      // computed or stored; the per-pair ft stays the zero the list rebuild wrote.
      const double slip = kFriction ? -dvx * ny + dvy * nx - (om[j] * r[j] + om[i] * r[i]) : 0.0;  // eq. 2.7
      const std::int32_t kind = species[i] * species_count + species[j];
      double history_overlap = overlap_max[q];
      double history_spring = kFriction ? spring[q] : 0.0;
      const double previous_max = history_overlap;
      const double trial = history_spring + slip * dt;
      const double fn = Law::force(normal[kind], overlap, overlap_rate, history_overlap);
      const double f_t = kFriction ? tangential_force(tangential[kind], fn, slip * dt, history_spring) : 0.0;
      if constexpr (kLedger) {
        // Sliding loses |F_t| times the slip the spring did not take; a contact that ends
        // banks its committed hysteresis; a dashpot loses its power over the step.
        if constexpr (kFriction) loss_friction += touching ? std::abs(f_t * (trial - history_spring)) : 0.0;
        loss_normal += touching ? Law::dashpot_power(normal[kind], overlap, overlap_rate) * dt
                                : Law::committed_loss(normal[kind], previous_max);
      }
      overlap_max[q] = touching ? history_overlap : 0.0;
      if constexpr (kFriction) spring[q] = touching ? history_spring : 0.0;
      const double fn_on = touching ? fn : 0.0, ft_on = touching ? f_t : 0.0;
      // Force on i: normal pushes i away from j, tangential acts along s = (-ny, nx).
      fx[q] = -fn_on * nx - ft_on * ny;
      fy[q] = -fn_on * ny + ft_on * nx;
      if constexpr (kFriction) ft[q] = ft_on;
      // The guard watches impacts (loading faster than impact_rate), not the permanent set of
      // a static hysteretic contact.
      worst = std::max(worst, touching && overlap_rate > impact_rate ? overlap / rsum : 0.0);
    }
    return {worst, loss_normal, loss_friction};
  }
};

}  // namespace

template <class Law, bool kLedger, bool kFriction>
PassSums World::pair_forces() {
  const auto& p = particles_;
  auto& c = pairs_;
  const int ns = table_.species_count;
  std::vector<typename Law::Coefficients> normal(table_.pair.size());
  std::vector<CundallStrack> tangential(table_.pair.size());
  for (std::size_t k = 0; k < table_.pair.size(); ++k) {
    normal[k] = normal_coefficients<Law>(table_.pair[k]);
    tangential[k] = table_.pair[k].tangential;
  }
  const PairKernel<Law, kLedger, kFriction> kernel{p.x.data(), p.y.data(), p.vx.data(), p.vy.data(), p.omega.data(),
                               p.radius.data(), p.species.data(), c.i.data(), c.j.data(),
                               normal.data(), tangential.data(), ns, settings_.dt, settings_.impact_rate,
                               c.overlap_max.data(), c.tangential_spring.data(), c.fx.data(),
                               c.fy.data(), c.ft.data()};
  const auto n = static_cast<std::int64_t>(c.size());
  const int threads = settings_.threads;
  if (!kLedger) {  // forces are per pair: any split gives the same bits
    if (threads == 1) return kernel(0, n);
    PassSums part[kMaxThreads] = {};
#pragma omp parallel num_threads(threads)
    {
      const std::int64_t t = omp_get_thread_num(), T = omp_get_num_threads();
      part[t] = kernel(n * t / T, n * (t + 1) / T);
    }
    PassSums total;
    for (int t = 0; t < threads; ++t) total.worst = std::max(total.worst, part[t].worst);
    return total;
  }
  // The ledger's sums are taken over fixed blocks of pairs and the blocks added in order, so
  // they are the same bits for every thread count (a resumed run may use another, SPEC §8).
  constexpr std::int64_t kBlock = 256;  // small enough to balance two threads on a few thousand pairs
  const std::int64_t blocks = (n + kBlock - 1) / kBlock;
  ledger_blocks_.resize(static_cast<std::size_t>(blocks));
#pragma omp parallel for num_threads(threads) if (threads > 1) schedule(static)
  for (std::int64_t b = 0; b < blocks; ++b)
    ledger_blocks_[b] = kernel(b * kBlock, std::min(n, (b + 1) * kBlock));
  PassSums total;
  for (const PassSums& part : ledger_blocks_) {
    total.worst = std::max(total.worst, part.worst);
    total.loss_normal += part.loss_normal;
    total.loss_friction += part.loss_friction;
  }
  return total;
}

// Disc–wall contacts: few, so a plain loop. The wall plays j with zero velocity (SPEC §2).
template <class Law, bool kLedger, bool kFriction>
PassSums World::wall_forces() {
  const auto& p = particles_;
  auto& c = wall_contacts_;
  const auto n = static_cast<std::int64_t>(c.size());
  const double dt = settings_.dt;
  double worst = 0, loss_normal = 0, loss_friction = 0;
  // Few contacts: one thread, so the ledger's sums are in a fixed order.
#pragma omp parallel for num_threads(settings_.threads) if (settings_.threads > 1 && !kLedger) \
    schedule(static) reduction(max : worst) reduction(+ : loss_normal, loss_friction)
  for (std::int64_t q = 0; q < n; ++q) {
    const std::int32_t i = c.disc[q];
    const Segment& s = segments_[c.segment[q]];
    const WallTouch touch = wall_touch(s, {p.x[i], p.y[i]}, p.radius[i]);
    const bool touching = s.active && touch.acts && touch.gap < p.radius[i];
    const Eigen::Vector2d& normal = touch.normal;
    const double overlap = p.radius[i] - touch.gap;
    const double overlap_rate = p.vx[i] * normal.x() + p.vy[i] * normal.y();
    const PairCoefficients& k = table_.wall[p.species[i]];
    double history_overlap = c.overlap_max[q];
    const double previous_max = history_overlap;
    const auto coefficients = normal_coefficients<Law>(k);
    const double fn = Law::force(coefficients, overlap, overlap_rate, history_overlap);
    double ft = 0;
    if constexpr (kFriction) {
      const double slip = p.vx[i] * normal.y() - p.vy[i] * normal.x() - p.omega[i] * p.radius[i];
      double history_spring = c.tangential_spring[q];
      const double trial = history_spring + slip * dt;
      ft = tangential_force(k.tangential, fn, slip * dt, history_spring);
      c.tangential_spring[q] = touching ? history_spring : 0.0;
      if constexpr (kLedger) loss_friction += touching ? std::abs(ft * (trial - history_spring)) : 0.0;
    }
    if constexpr (kLedger) {
      loss_normal += touching ? Law::dashpot_power(coefficients, overlap, overlap_rate) * dt
                              : Law::committed_loss(coefficients, previous_max);
    }
    c.overlap_max[q] = touching ? history_overlap : 0.0;
    const double fn_on = touching ? fn : 0.0, ft_on = touching ? ft : 0.0;
    c.fx[q] = -fn_on * normal.x() - ft_on * normal.y();
    c.fy[q] = -fn_on * normal.y() + ft_on * normal.x();
    if constexpr (kFriction) c.ft[q] = ft_on;
    worst = std::max(worst, touching && overlap_rate > settings_.impact_rate
                                ? overlap / pass_through_overlap(s, p.radius[i]) : 0.0);
  }
  return {worst, loss_normal, loss_friction};
}

template <class Law, bool kFriction>
void World::compute_forces_with() {
  auto t0 = Clock::now();
  const bool ledger = settings_.track_energy;
  const PassSums pairs = ledger ? pair_forces<Law, true, kFriction>() : pair_forces<Law, false, kFriction>();
  profile_.pair_forces += seconds_since(t0);
  t0 = Clock::now();
  const PassSums walls = ledger ? wall_forces<Law, true, kFriction>() : wall_forces<Law, false, kFriction>();
  profile_.wall_forces += seconds_since(t0);
  ledger_.normal += pairs.loss_normal + walls.loss_normal;
  ledger_.friction += pairs.loss_friction + walls.loss_friction;
  check_overlap(std::max(pairs.worst, walls.worst));
}

template <bool kFriction>
void World::compute_forces_for() {
  switch (settings_.normal_model) {
    case NormalModel::walton_braun: compute_forces_with<WaltonBraun, kFriction>(); break;
    case NormalModel::linear_dashpot: compute_forces_with<LinearDashpot, kFriction>(); break;
    case NormalModel::hertz: compute_forces_with<Hertz, kFriction>(); break;
  }
}

void World::compute_forces() {
  if (frictional_) compute_forces_for<true>();
  else compute_forces_for<false>();
}

// SPEC §8: an overlap beyond the guard means the contact is far stiffer-demanding than the
// stiffness was designed for (too fast an impact, too large a step): stop with advice.
void World::check_overlap(double worst) {
  worst *= guard_radius_scale_;
  peak_impact_overlap_ = std::max(peak_impact_overlap_, worst);
  if (!(worst > settings_.overlap_guard)) return;
  const auto& p = particles_;
  std::int64_t a = -1, b = -1;
  double found = 0;
  for (std::size_t q = 0; q < pairs_.size(); ++q) {
    const std::int32_t i = pairs_.i[q], j = pairs_.j[q];
    const double d = std::hypot(p.x[j] - p.x[i], p.y[j] - p.y[i]);
    const double ratio = (p.radius[i] + p.radius[j] - d) / (p.radius[i] + p.radius[j]);
    if (ratio > found) { found = ratio; a = p.id[i]; b = p.id[j]; }
  }
  std::ostringstream msg;
  msg << "an impact overlap of " << static_cast<int>(100 * worst)
      << " % of the depth at which the contact is passed through (guard: "
      << static_cast<int>(100 * settings_.overlap_guard) << " %) at step " << steps_ << " (t* = "
      << time_ / settings_.unit_time << ")";
  if (a >= 0 && found * guard_radius_scale_ >= worst * 0.999) msg << " between discs " << a << " and " << b;
  else msg << " against a wall";
  msg << ": an impact faster than the contact stiffness was designed for, or too large a step. "
         "Raise contact.design_impact_speed (stiffer contacts) or lower contact.design_max_overlap, "
         "and/or lower integration.dt_fraction";
  throw NumericalError(msg.str());
}

// Sum of the contact forces on disc k plus gravity, as accelerations (eqs. 2.10–2.11): its own
// row of pairs (k = i), then its incoming pairs (k = j, Newton's third law), then its walls.
// Torque r F_t has the same sign on both discs of a pair.
struct ForceSum {
  const double* pair_fx; const double* pair_fy; const double* pair_ft;
  const std::int32_t* row_start; const std::int32_t* incoming_start; const std::int32_t* incoming;
  const double* wall_fx; const double* wall_fy; const double* wall_ft;
  const std::int32_t* wall_row_start;
  const double* inv_mass; const double* inv_inertia; const double* radius;
  double gx, gy;

  void operator()(std::int64_t k, double& ax, double& ay, double& alpha) const {
    double fx = 0, fy = 0, ft = 0;
    for (std::int32_t q = row_start[k]; q < row_start[k + 1]; ++q) {
      fx += pair_fx[q]; fy += pair_fy[q]; ft += pair_ft[q];
    }
    for (std::int32_t e = incoming_start[k]; e < incoming_start[k + 1]; ++e) {
      const std::int32_t q = incoming[e];
      fx -= pair_fx[q]; fy -= pair_fy[q]; ft += pair_ft[q];
    }
    for (std::int32_t q = wall_row_start[k]; q < wall_row_start[k + 1]; ++q) {
      fx += wall_fx[q]; fy += wall_fy[q]; ft += wall_ft[q];
    }
    ax = fx * inv_mass[k] + gx;
    ay = fy * inv_mass[k] + gy;
    alpha = ft * radius[k] * inv_inertia[k];
  }
};

namespace {

// Local non-viscous damping (Cundall's, as in PFC): a - share |a| sgn(v) per component. It
// removes kinetic energy without touching equilibrium (a resting disc feels nothing), so a
// pile damped to rest is at rest under the undamped law too. Preparation only.
inline void damp(double share, std::int64_t lo, std::int64_t hi, double* ax, double* ay,
                 double* alpha, const double* vx, const double* vy, const double* om) {
  auto sgn = [](double v) { return static_cast<double>((v > 0) - (v < 0)); };
  for (std::int64_t k = lo; k < hi; ++k) {
    ax[k] -= share * std::abs(ax[k]) * sgn(vx[k]);
    ay[k] -= share * std::abs(ay[k]) * sgn(vy[k]);
    alpha[k] -= share * std::abs(alpha[k]) * sgn(om[k]);
  }
}

// Runs body(begin, end, thread) over contiguous blocks of [0, n), one per thread.
template <class Body>
void for_blocks(std::int64_t n, int threads, const Body& body) {
  if (threads <= 1) {
    body(0, n, 0);
    return;
  }
#pragma omp parallel num_threads(threads)
  {
    const std::int64_t t = omp_get_thread_num(), T = omp_get_num_threads();
    body(n * t / T, n * (t + 1) / T, static_cast<int>(t));
  }
}

}  // namespace

ForceSum World::force_sum() const {
  const auto& c = pairs_;
  const auto& w = wall_contacts_;
  const auto& p = particles_;
  return ForceSum{c.fx.data(), c.fy.data(), c.ft.data(), c.row_start.data(),
                  c.incoming_start.data(), c.incoming.data(), w.fx.data(), w.fy.data(),
                  w.ft.data(), w.row_start.data(), p.inv_mass.data(), p.inv_inertia.data(),
                  p.radius.data(), settings_.gravity.x(), settings_.gravity.y()};
}

// Per-thread results of an integration pass, combined in a fixed order.
struct PassResult {
  double max_displacement2 = 0;
  bool finite = true;
};

// Semi-implicit Euler, the seed's integrator (eqs. 2.15–2.18): v += a dt, then x += v dt.
void World::integrate_symplectic_euler() {
  auto& p = particles_;
  const ForceSum sum = force_sum();
  const double dt = settings_.dt, damping = settings_.local_damping;
  double* __restrict x = p.x.data(); double* __restrict y = p.y.data();
  double* __restrict vx = p.vx.data(); double* __restrict vy = p.vy.data();
  double* __restrict om = p.omega.data(); double* __restrict angle = p.angle.data();
  const double* __restrict x0 = x_at_rebuild_.data(); const double* __restrict y0 = y_at_rebuild_.data();
  PassResult results[kMaxThreads];
  double* __restrict ax = p.ax.data(); double* __restrict ay = p.ay.data();
  double* __restrict alpha = p.alpha.data();
  for_blocks(static_cast<std::int64_t>(p.size()), settings_.threads,
             [&](std::int64_t lo, std::int64_t hi, int t) {
    double max_d2 = 0;
    bool finite = true;
    // The sums first (scalar, data-dependent lengths), then the update as a plain loop the
    // compiler vectorises.
    for (std::int64_t k = lo; k < hi; ++k) sum(k, ax[k], ay[k], alpha[k]);
    if (damping > 0) damp(damping, lo, hi, ax, ay, alpha, vx, vy, om);
#pragma omp simd reduction(max : max_d2) reduction(&& : finite)
    for (std::int64_t k = lo; k < hi; ++k) {
      vx[k] += ax[k] * dt;
      vy[k] += ay[k] * dt;
      om[k] += alpha[k] * dt;
      x[k] += vx[k] * dt;
      y[k] += vy[k] * dt;
      angle[k] += om[k] * dt;
      const double ddx = x[k] - x0[k], ddy = y[k] - y0[k];
      max_d2 = std::max(max_d2, ddx * ddx + ddy * ddy);
      finite = finite && std::isfinite(x[k] + y[k] + vx[k] + vy[k] + om[k]);
    }
    results[t] = {max_d2, finite};
  });
  finish_pass(results);
}

// Velocity Verlet, first half: v(t+dt/2) = v + a dt/2; x += v(t+dt/2) dt.
void World::verlet_half_kick_and_drift() {
  auto& p = particles_;
  const double dt = settings_.dt, h = 0.5 * dt;
  double* __restrict x = p.x.data(); double* __restrict y = p.y.data();
  double* __restrict vx = p.vx.data(); double* __restrict vy = p.vy.data();
  double* __restrict om = p.omega.data(); double* __restrict angle = p.angle.data();
  const double* __restrict ax = p.ax.data(); const double* __restrict ay = p.ay.data();
  const double* __restrict alpha = p.alpha.data();
  const double* __restrict x0 = x_at_rebuild_.data(); const double* __restrict y0 = y_at_rebuild_.data();
  PassResult results[kMaxThreads];
  for_blocks(static_cast<std::int64_t>(p.size()), settings_.threads,
             [&](std::int64_t lo, std::int64_t hi, int t) {
    double max_d2 = 0;
    for (std::int64_t k = lo; k < hi; ++k) {
      vx[k] += ax[k] * h;
      vy[k] += ay[k] * h;
      om[k] += alpha[k] * h;
      x[k] += vx[k] * dt;
      y[k] += vy[k] * dt;
      angle[k] += om[k] * dt;
      const double ddx = x[k] - x0[k], ddy = y[k] - y0[k];
      max_d2 = std::max(max_d2, ddx * ddx + ddy * ddy);
    }
    results[t] = {max_d2, true};
  });
  finish_pass(results);
}

// Velocity Verlet, second half: forces at the new positions (with the half-step velocities),
// then v(t+dt) = v(t+dt/2) + a(t+dt) dt/2.
void World::verlet_half_kick() {
  auto& p = particles_;
  const ForceSum sum = force_sum();
  const double h = 0.5 * settings_.dt, damping = settings_.local_damping;
  const double* __restrict x = p.x.data(); const double* __restrict y = p.y.data();
  double* __restrict vx = p.vx.data(); double* __restrict vy = p.vy.data();
  double* __restrict om = p.omega.data();
  double* __restrict ax = p.ax.data(); double* __restrict ay = p.ay.data();
  double* __restrict alpha = p.alpha.data();
  PassResult results[kMaxThreads];
  for_blocks(static_cast<std::int64_t>(p.size()), settings_.threads,
             [&](std::int64_t lo, std::int64_t hi, int t) {
    bool finite = true;
    for (std::int64_t k = lo; k < hi; ++k) sum(k, ax[k], ay[k], alpha[k]);
    if (damping > 0) damp(damping, lo, hi, ax, ay, alpha, vx, vy, om);
    for (std::int64_t k = lo; k < hi; ++k) {
      vx[k] += ax[k] * h;
      vy[k] += ay[k] * h;
      om[k] += alpha[k] * h;
      finite &= std::isfinite(x[k] + y[k] + vx[k] + vy[k] + om[k]);
    }
    results[t] = {0.0, finite};
  });
  finish_pass(results);
}

void World::finish_pass(const PassResult* results) {
  bool finite = true;
  for (int t = 0; t < settings_.threads; ++t) {
    max_displacement2_ = std::max(max_displacement2_, results[t].max_displacement2);
    finite = finite && results[t].finite;
  }
  finite_ = finite;
}

EnergyState World::energy(double reference_y) const {
  EnergyState e;
  const auto& p = particles_;
  const double g = -settings_.gravity.y();
  for (std::size_t k = 0; k < p.size(); ++k) {
    e.translational += 0.5 * p.mass[k] * (p.vx[k] * p.vx[k] + p.vy[k] * p.vy[k]);
    e.rotational += 0.5 / p.inv_inertia[k] * p.omega[k] * p.omega[k];
    e.potential += p.mass[k] * g * (p.y[k] - reference_y);
  }
  // Springs of the touching contacts; the history arrays hold this step's state.
  auto add = [&](const PairCoefficients& k, double overlap, double overlap_max, double spring) {
    e.elastic += 0.5 * k.tangential.k_tangential * spring * spring;
    switch (settings_.normal_model) {
      case NormalModel::walton_braun:
        e.elastic += WaltonBraun::elastic_energy(k.walton_braun, overlap, overlap_max);
        e.committed_normal += WaltonBraun::committed_loss(k.walton_braun, overlap_max);
        break;
      case NormalModel::linear_dashpot: e.elastic += LinearDashpot::elastic_energy(k.linear_dashpot, overlap, 0); break;
      case NormalModel::hertz: e.elastic += Hertz::elastic_energy(k.hertz, overlap, 0); break;
    }
  };
  for (std::size_t q = 0; q < pairs_.size(); ++q) {
    const std::int32_t i = pairs_.i[q], j = pairs_.j[q];
    const double overlap = p.radius[i] + p.radius[j] - std::hypot(p.x[j] - p.x[i], p.y[j] - p.y[i]);
    if (overlap > 0)
      add(table_.between(p.species[i], p.species[j]), overlap, pairs_.overlap_max[q],
          frictional_ ? pairs_.tangential_spring[q] : 0.0);
  }
  for (std::size_t q = 0; q < wall_contacts_.size(); ++q) {
    const std::int32_t i = wall_contacts_.disc[q];
    const Segment& s = segments_[wall_contacts_.segment[q]];
    const WallTouch touch = wall_touch(s, {p.x[i], p.y[i]}, p.radius[i]);
    const double overlap = p.radius[i] - touch.gap;
    if (s.active && touch.acts && overlap > 0)
      add(table_.wall[p.species[i]], overlap, wall_contacts_.overlap_max[q],
          frictional_ ? wall_contacts_.tangential_spring[q] : 0.0);
  }
  return e;
}

double World::largest_overlap_share() const {
  const auto& p = particles_;
  double largest = 0;
  for (std::size_t q = 0; q < pairs_.size(); ++q) {
    const std::int32_t i = pairs_.i[q], j = pairs_.j[q];
    const double overlap = p.radius[i] + p.radius[j] - std::hypot(p.x[j] - p.x[i], p.y[j] - p.y[i]);
    largest = std::max(largest, overlap / std::min(p.radius[i], p.radius[j]));
  }
  for (std::size_t q = 0; q < wall_contacts_.size(); ++q) {
    const std::int32_t i = wall_contacts_.disc[q];
    const Segment& s = segments_[wall_contacts_.segment[q]];
    const WallTouch touch = wall_touch(s, {p.x[i], p.y[i]}, p.radius[i]);
    if (s.active && touch.acts) largest = std::max(largest, 1.0 - touch.gap / p.radius[i]);
  }
  return largest;
}

void World::check_escape(double margin) const {
  if (segments_.empty()) return;
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  for (const auto& s : segments_) {
    x0 = std::min({x0, s.a.x(), s.b.x()}); x1 = std::max({x1, s.a.x(), s.b.x()});
    y0 = std::min({y0, s.a.y(), s.b.y()}); y1 = std::max({y1, s.a.y(), s.b.y()});
  }
  const auto& p = particles_;
  for (std::size_t k = 0; k < p.size(); ++k) {
    // Above the walls is allowed (the pile box is open at the top); below or beside is not.
    if (p.y[k] < y0 - margin || p.x[k] < x0 - margin || p.x[k] > x1 + margin) {
      std::ostringstream msg;
      msg << "disc id " << p.id[k] << " left the domain at step " << steps_ << " (t* = "
          << time_ / settings_.unit_time << "), at (" << p.x[k] << ", " << p.y[k]
          << ") m, moving at (" << p.vx[k] << ", " << p.vy[k] << ") m/s: ";
      // One-sided walls cannot be squeezed through; a disc outside went over a wall's top, or
      // through a two-sided plate or more than a diameter through a face (walls.hpp).
      if (p.y[k] > y1 - margin)
        msg << "it flew over the top of a wall (raise the walls: avalanche.wall_height, or the "
               "scene's [[walls]])";
      else
        msg << "it was pushed through a wall (a two-sided plate once its centre crossed, or a "
               "face by more than its diameter): give the scene's walls an inside, or raise "
               "contact.design_impact_speed or lower integration.dt_fraction if the impact is "
               "far beyond the contact's design";
      throw NumericalError(msg.str());
    }
  }
}

void World::check_finite() const {
  if (finite_) return;
  const auto& p = particles_;
  for (std::size_t k = 0; k < p.size(); ++k) {
    if (!std::isfinite(p.x[k] + p.y[k] + p.vx[k] + p.vy[k] + p.omega[k])) {
      std::ostringstream msg;
      msg << "non-finite state at step " << steps_ << " (t* = "
          << time_ / settings_.unit_time << ") for disc id " << p.id[k]
          << ": the time step is too large for the contact stiffness; lower "
             "integration.dt_fraction or contact.design_impact_speed / raise "
             "contact.design_max_overlap";
      throw NumericalError(msg.str());
    }
  }
}

void World::step() {
  if (settings_.reorder_every > 0 && steps_ % settings_.reorder_every == 0) reorder_discs();
  const double half_skin = 0.5 * settings_.skin;
  auto needs_rebuild = [&] {
    return !lists_valid_ || std::sqrt(max_displacement2_) + max_growth_ >= half_skin;
  };
  if (settings_.integrator == IntegratorKind::symplectic_euler) {
    if (needs_rebuild()) rebuild_lists();
    compute_forces();
    const auto t0 = Clock::now();
    integrate_symplectic_euler();
    profile_.integrate += seconds_since(t0);
  } else {
    if (!lists_valid_) {  // first step: accelerations at the initial state
      rebuild_lists();
      compute_forces();
      auto& p = particles_;
      const ForceSum sum = force_sum();
      for (std::size_t k = 0; k < p.size(); ++k) sum(k, p.ax[k], p.ay[k], p.alpha[k]);
    }
    auto t0 = Clock::now();
    verlet_half_kick_and_drift();
    profile_.integrate += seconds_since(t0);
    if (needs_rebuild()) rebuild_lists();
    compute_forces();
    t0 = Clock::now();
    verlet_half_kick();
    profile_.integrate += seconds_since(t0);
  }
  time_ += settings_.dt;
  ++steps_;
  check_finite();
}

}  // namespace runout

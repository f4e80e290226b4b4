#include "runout/world.hpp"

#include <chrono>
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
      table_(std::move(table)), settings_(settings) {
  settings_.threads = std::max(1, settings_.threads);
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

void World::set_velocity(std::size_t k, double vx, double vy, double omega) {
  particles_.vx[k] = vx;
  particles_.vy[k] = vy;
  particles_.omega[k] = omega;
}

void World::restore_history(const PairContacts& pairs, const WallContacts& walls) {
  pairs_ = pairs;
  wall_contacts_ = walls;
  // The search keeps the history of (i, j) keys present in the lists it replaces.
  rebuild_lists();
}

void World::rebuild_lists() {
  const auto t0 = Clock::now();
  search_.rebuild(particles_, segments_, settings_.skin, settings_.threads, pairs_,
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
// and its history is forgotten (the contact has broken).
template <class Law>
void World::pair_forces() {
  const auto& p = particles_;
  auto& c = pairs_;
  const auto n = static_cast<std::int64_t>(c.size());
  const double dt = settings_.dt;
  const int ns = table_.species_count;
  const double* __restrict x = p.x.data();
  const double* __restrict y = p.y.data();
  const double* __restrict vx = p.vx.data();
  const double* __restrict vy = p.vy.data();
  const double* __restrict om = p.omega.data();
  const double* __restrict r = p.radius.data();
  const std::int32_t* __restrict sp = p.species.data();
  const std::int32_t* __restrict pi = c.i.data();
  const std::int32_t* __restrict pj = c.j.data();
  double* __restrict overlap_max = c.overlap_max.data();
  double* __restrict spring = c.tangential_spring.data();
  double* __restrict out_fx = c.fx.data();
  double* __restrict out_fy = c.fy.data();
  double* __restrict out_ft = c.ft.data();
  const PairCoefficients* __restrict coef = table_.pair.data();

#pragma omp parallel for simd num_threads(settings_.threads) if (settings_.threads > 1) \
    schedule(static)
  for (std::int64_t q = 0; q < n; ++q) {
    const std::int32_t i = pi[q], j = pj[q];
    const double dx = x[j] - x[i], dy = y[j] - y[i];
    const double dist2 = dx * dx + dy * dy;
    const double rsum = r[i] + r[j];
    const bool touching = dist2 < rsum * rsum;
    const double dist = std::sqrt(dist2);
    // Coincident centres have no normal; the zero vector keeps the force finite (eq. 2.2).
    const double inv_dist = dist > 0 ? 1.0 / dist : 0.0;
    const double nx = dx * inv_dist, ny = dy * inv_dist;
    const double overlap = rsum - dist;                                  // eq. 2.1
    const double dvx = vx[j] - vx[i], dvy = vy[j] - vy[i];
    const double overlap_rate = -(dvx * nx + dvy * ny);
    const double slip = -dvx * ny + dvy * nx - (om[j] * r[j] + om[i] * r[i]);  // eq. 2.7
    const PairCoefficients& k = coef[sp[i] * ns + sp[j]];
    double history_overlap = overlap_max[q];
    double history_spring = spring[q];
    const double fn = Law::force(normal_coefficients<Law>(k), overlap, overlap_rate,
                                 history_overlap);
    const double ft = tangential_force(k.tangential, fn, slip * dt, history_spring);
    overlap_max[q] = touching ? history_overlap : 0.0;
    spring[q] = touching ? history_spring : 0.0;
    const double fn_on = touching ? fn : 0.0, ft_on = touching ? ft : 0.0;
    // Force on i: normal pushes i away from j, tangential acts along s = (-ny, nx).
    out_fx[q] = -fn_on * nx - ft_on * ny;
    out_fy[q] = -fn_on * ny + ft_on * nx;
    out_ft[q] = ft_on;
  }
}

// Disc–wall contacts: few, so a plain loop. The wall plays j with zero velocity (SPEC §2).
template <class Law>
void World::wall_forces() {
  const auto& p = particles_;
  auto& c = wall_contacts_;
  const auto n = static_cast<std::int64_t>(c.size());
  const double dt = settings_.dt;
#pragma omp parallel for num_threads(settings_.threads) if (settings_.threads > 1 && n > 4096) \
    schedule(static)
  for (std::int64_t q = 0; q < n; ++q) {
    const std::int32_t i = c.disc[q];
    const Segment& s = segments_[c.segment[q]];
    const Eigen::Vector2d centre(p.x[i], p.y[i]);
    const SegmentProjection proj = project(s, centre);
    const Eigen::Vector2d d = proj.point - centre;
    const double dist = d.norm();
    const bool touching = s.active && !proj.at_free_end && dist < p.radius[i];
    const Eigen::Vector2d normal = dist > 0 ? Eigen::Vector2d(d / dist) : Eigen::Vector2d(0, 0);
    const double overlap = p.radius[i] - dist;
    const double overlap_rate = p.vx[i] * normal.x() + p.vy[i] * normal.y();
    const double slip = p.vx[i] * normal.y() - p.vy[i] * normal.x() - p.omega[i] * p.radius[i];
    const PairCoefficients& k = table_.wall[p.species[i]];
    double history_overlap = c.overlap_max[q];
    double history_spring = c.tangential_spring[q];
    const double fn = Law::force(normal_coefficients<Law>(k), overlap, overlap_rate,
                                 history_overlap);
    const double ft = tangential_force(k.tangential, fn, slip * dt, history_spring);
    c.overlap_max[q] = touching ? history_overlap : 0.0;
    c.tangential_spring[q] = touching ? history_spring : 0.0;
    const double fn_on = touching ? fn : 0.0, ft_on = touching ? ft : 0.0;
    c.fx[q] = -fn_on * normal.x() - ft_on * normal.y();
    c.fy[q] = -fn_on * normal.y() + ft_on * normal.x();
    c.ft[q] = ft_on;
  }
}

void World::compute_forces() {
  auto t0 = Clock::now();
  switch (settings_.normal_model) {
    case NormalModel::walton_braun: pair_forces<WaltonBraun>(); break;
    case NormalModel::linear_dashpot: pair_forces<LinearDashpot>(); break;
    case NormalModel::hertz: pair_forces<Hertz>(); break;
  }
  profile_.pair_forces += seconds_since(t0);
  t0 = Clock::now();
  switch (settings_.normal_model) {
    case NormalModel::walton_braun: wall_forces<WaltonBraun>(); break;
    case NormalModel::linear_dashpot: wall_forces<LinearDashpot>(); break;
    case NormalModel::hertz: wall_forces<Hertz>(); break;
  }
  profile_.wall_forces += seconds_since(t0);
}

inline void World::acceleration(std::size_t k, double& ax, double& ay, double& alpha) const {
  const auto& c = pairs_;
  double fx = 0, fy = 0, ft = 0;
  for (std::int32_t e = c.gather_start[k]; e < c.gather_start[k + 1]; ++e) {
    const std::int32_t entry = c.gather[e];
    const std::int32_t q = entry >> 1;
    const double sign = (entry & 1) ? -1.0 : 1.0;  // Newton's third law for j
    fx += sign * c.fx[q];
    fy += sign * c.fy[q];
    ft += c.ft[q];  // torque r F_t has the same sign on both discs (eq. 2.11)
  }
  const auto& w = wall_contacts_;
  for (std::int32_t q = w.row_start[k]; q < w.row_start[k + 1]; ++q) {
    fx += w.fx[q];
    fy += w.fy[q];
    ft += w.ft[q];
  }
  const auto& p = particles_;
  ax = fx * p.inv_mass[k] + settings_.gravity.x();  // eq. 2.10
  ay = fy * p.inv_mass[k] + settings_.gravity.y();
  alpha = ft * p.radius[k] * p.inv_inertia[k];  // eq. 2.11
}

// Semi-implicit Euler, the seed's integrator (eqs. 2.15–2.18): v += a dt, then x += v dt.
void World::integrate_symplectic_euler() {
  auto& p = particles_;
  const auto n = static_cast<std::int64_t>(p.size());
  const double dt = settings_.dt;
  double max_d2 = 0;
  bool finite = true;
#pragma omp parallel for num_threads(settings_.threads) if (settings_.threads > 1) \
    schedule(static) reduction(max : max_d2) reduction(&& : finite)
  for (std::int64_t k = 0; k < n; ++k) {
    double ax, ay, alpha;
    acceleration(k, ax, ay, alpha);
    p.vx[k] += ax * dt;
    p.vy[k] += ay * dt;
    p.omega[k] += alpha * dt;
    p.x[k] += p.vx[k] * dt;
    p.y[k] += p.vy[k] * dt;
    p.angle[k] += p.omega[k] * dt;
    const double ddx = p.x[k] - x_at_rebuild_[k], ddy = p.y[k] - y_at_rebuild_[k];
    max_d2 = std::max(max_d2, ddx * ddx + ddy * ddy);
    finite = finite && std::isfinite(p.x[k] + p.y[k] + p.vx[k] + p.vy[k] + p.omega[k]);
  }
  max_displacement2_ = std::max(max_displacement2_, max_d2);
  finite_ = finite;
}

// Velocity Verlet, first half: v(t+dt/2) = v + a dt/2; x += v(t+dt/2) dt.
void World::verlet_half_kick_and_drift() {
  auto& p = particles_;
  const auto n = static_cast<std::int64_t>(p.size());
  const double dt = settings_.dt, h = 0.5 * dt;
  double max_d2 = 0;
#pragma omp parallel for num_threads(settings_.threads) if (settings_.threads > 1) \
    schedule(static) reduction(max : max_d2)
  for (std::int64_t k = 0; k < n; ++k) {
    p.vx[k] += p.ax[k] * h;
    p.vy[k] += p.ay[k] * h;
    p.omega[k] += p.alpha[k] * h;
    p.x[k] += p.vx[k] * dt;
    p.y[k] += p.vy[k] * dt;
    p.angle[k] += p.omega[k] * dt;
    const double ddx = p.x[k] - x_at_rebuild_[k], ddy = p.y[k] - y_at_rebuild_[k];
    max_d2 = std::max(max_d2, ddx * ddx + ddy * ddy);
  }
  max_displacement2_ = std::max(max_displacement2_, max_d2);
}

// Velocity Verlet, second half: forces at the new positions (with the half-step velocities),
// then v(t+dt) = v(t+dt/2) + a(t+dt) dt/2.
void World::verlet_half_kick() {
  auto& p = particles_;
  const auto n = static_cast<std::int64_t>(p.size());
  const double h = 0.5 * settings_.dt;
  bool finite = true;
#pragma omp parallel for num_threads(settings_.threads) if (settings_.threads > 1) \
    schedule(static) reduction(&& : finite)
  for (std::int64_t k = 0; k < n; ++k) {
    acceleration(k, p.ax[k], p.ay[k], p.alpha[k]);
    p.vx[k] += p.ax[k] * h;
    p.vy[k] += p.ay[k] * h;
    p.omega[k] += p.alpha[k] * h;
    finite = finite && std::isfinite(p.x[k] + p.y[k] + p.vx[k] + p.vy[k] + p.omega[k]);
  }
  finite_ = finite;
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
      for (std::size_t k = 0; k < p.size(); ++k) acceleration(k, p.ax[k], p.ay[k], p.alpha[k]);
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

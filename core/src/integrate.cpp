// Force sums and the kick–drift both integrators are made of (SPEC §2, eqs. 2.15–2.18):
//   symplectic Euler: gather, v += a dt, x += v dt
//   velocity Verlet:  v += a dt/2, x += v dt | forces | gather, v += a dt/2
#include <cmath>
#include <limits>

#include "step_phases.hpp"

namespace runout::phases {

namespace {

// The sum of the contact forces and torques on each disc of [lo, hi) plus gravity, as
// accelerations (eqs. 2.10–2.11): its run of pair pushes (a slice's discs side by side, one
// lane each, so each disc's additions stay in its run's order), then its walls, then
// F / m + g. The additions are 0 + row + incoming + walls in that order whatever the thread
// count. `lo` starts a window of lanes (DiscRuns::kWindow), `hi` too or is n.
void accelerations(const PairContacts& c, const WallContacts& w, const DiscRuns& runs,
                   std::int64_t lo, std::int64_t hi, double gx, double gy,
                   const double* __restrict inv_mass, const double* __restrict inv_inertia,
                   const Accelerations& a) {
  constexpr std::int64_t L = DiscRuns::kSlice;
  // An empty block starts at n, which need not start a slice: its first slice would be the
  // last slice of the block before, summed here a second time by another thread (a race on
  // that slice's accelerations, seen with fewer discs than threads have windows).
  if (lo >= hi) return;
  const double* __restrict fx = c.fx.data();
  const double* __restrict fy = c.fy.data();
  const double* __restrict torque = c.torque.data();
  const std::int32_t* __restrict slice_start = runs.slice_start.data();
  const std::int32_t* __restrict src = runs.source.data();
  const std::int32_t* __restrict lane_disc = runs.lane_disc.data();
  double* __restrict ax = a.x;
  double* __restrict ay = a.y;
  double* __restrict alpha = a.angular;
  const std::int64_t first = a.first;
  for (std::int64_t g = lo / L; g * L < hi; ++g) {
    double sx[L] = {}, sy[L] = {}, st[L] = {};
    for (std::int64_t s = slice_start[g]; s < slice_start[g + 1]; s += L)
      for (std::int64_t l = 0; l < L; ++l) {
        const std::int32_t e = src[s + l];
        sx[l] += fx[e]; sy[l] += fy[e]; st[l] += torque[e];
      }
    for (std::int64_t l = 0; l < L; ++l)
      if (const std::int32_t k = lane_disc[g * L + l]; k >= 0) {
        ax[k - first] = sx[l]; ay[k - first] = sy[l]; alpha[k - first] = st[l];
      }
  }
  // Few discs touch a wall: adding their contacts after all rows keeps each disc's order
  // (walls last, by segment) without a loop per disc.
  for (std::int32_t q = w.row_start[lo]; q < w.row_start[hi]; ++q) {
    const std::int64_t k = w.disc[q] - first;
    ax[k] += w.fx[q]; ay[k] += w.fy[q]; alpha[k] += w.torque[q];
  }
  for (std::int64_t k = lo; k < hi; ++k) {
    ax[k - first] = ax[k - first] * inv_mass[k] + gx;
    ay[k - first] = ay[k - first] * inv_mass[k] + gy;
    alpha[k - first] = alpha[k - first] * inv_inertia[k];
  }
}

// Local non-viscous damping (Cundall's, as in PFC): a - share |a| sgn(v) per component. It
// removes kinetic energy without touching equilibrium (a resting disc feels nothing), so a
// pile damped to rest is at rest under the undamped law too. Preparation only.
void damp(double share, std::int64_t lo, std::int64_t hi, double* __restrict ax,
          double* __restrict ay, double* __restrict alpha, const double* __restrict vx,
          const double* __restrict vy, const double* __restrict om) {
  auto sgn = [](double v) { return static_cast<double>((v > 0) - (v < 0)); };
  for (std::int64_t k = lo; k < hi; ++k) {
    ax[k] -= share * std::abs(ax[k]) * sgn(vx[k]);
    ay[k] -= share * std::abs(ay[k]) * sgn(vy[k]);
    alpha[k] -= share * std::abs(alpha[k]) * sgn(om[k]);
  }
}

// v += a kick, x += v drift over [lo, hi), and how far the discs are from where the lists
// were built. Parameters rather than captures, so the compiler sees the arrays cannot alias.
Motion kick_drift(std::int64_t lo, std::int64_t hi, double kick, double drift,
                  double* __restrict x, double* __restrict y, double* __restrict vx,
                  double* __restrict vy, double* __restrict om, double* __restrict angle,
                  const double* __restrict ax, const double* __restrict ay,
                  const double* __restrict alpha, const double* __restrict x0,
                  const double* __restrict y0) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  double ux_lo = inf, ux_hi = -inf, uy_lo = inf, uy_hi = -inf, u2 = 0, poison = 0;
#pragma omp simd reduction(min : ux_lo, uy_lo) reduction(max : ux_hi, uy_hi, u2) reduction(+ : poison)
  for (std::int64_t k = lo; k < hi; ++k) {
    vx[k] += ax[k] * kick;
    vy[k] += ay[k] * kick;
    om[k] += alpha[k] * kick;
    x[k] += vx[k] * drift;
    y[k] += vy[k] * drift;
    angle[k] += om[k] * drift;
    const double ux = x[k] - x0[k], uy = y[k] - y0[k];
    ux_lo = std::min(ux_lo, ux); ux_hi = std::max(ux_hi, ux);
    uy_lo = std::min(uy_lo, uy); uy_hi = std::max(uy_hi, uy);
    u2 = std::max(u2, ux * ux + uy * uy);
    // 0 for finite values, NaN once any is infinite or NaN (std::max would pass over a NaN).
    poison += (x[k] + y[k] + vx[k] + vy[k] + om[k]) * 0.0;
  }
  return {ux_lo, ux_hi, uy_lo, uy_hi, u2, poison == 0.0};
}

}  // namespace

Motion Motion::merge(const Motion& a, const Motion& b) {
  return {std::min(a.ux_lo, b.ux_lo), std::max(a.ux_hi, b.ux_hi),
          std::min(a.uy_lo, b.uy_lo), std::max(a.uy_hi, b.uy_hi),
          std::max(a.max_displacement2, b.max_displacement2), a.finite && b.finite};
}

double Motion::spread() const {
  if (!finite) return std::numeric_limits<double>::infinity();
  if (!(ux_lo <= ux_hi)) return 0.0;
  return std::hypot(ux_hi - ux_lo, uy_hi - uy_lo);
}

Motion advance(const StepContext& step, Particles& p, const PairContacts& c,
               const WallContacts& w, const DiscRuns& runs, const HotArray<double>& x_at_rebuild,
               const HotArray<double>& y_at_rebuild, std::int64_t lo, std::int64_t hi,
               bool gather, double kick, double drift, const Accelerations& a) {
  const StepSettings& st = step.settings;
  // The kick and drift see disc k's acceleration at [k - a.first]: offset views of the
  // discs' arrays from lo, so one loop serves every layout of them.
  const std::int64_t count = hi - lo, at = lo - a.first;
  if (count <= 0) return Motion{};
  if (gather) {
    accelerations(c, w, runs, lo, hi, st.gravity.x(), st.gravity.y(), p.inv_mass.data(),
                  p.inv_inertia.data(), a);
    if (st.local_damping > 0)
      damp(st.local_damping, 0, count, a.x + at, a.y + at, a.angular + at, p.vx.data() + lo,
           p.vy.data() + lo, p.omega.data() + lo);
  }
  return kick_drift(0, count, kick, drift, p.x.data() + lo, p.y.data() + lo, p.vx.data() + lo,
                    p.vy.data() + lo, p.omega.data() + lo, p.angle.data() + lo, a.x + at, a.y + at,
                    a.angular + at, x_at_rebuild.data() + lo, y_at_rebuild.data() + lo);
}

}  // namespace runout::phases

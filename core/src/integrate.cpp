// Force sums and the kick–drift both integrators are made of (SPEC §2, eqs. 2.15–2.18):
//   symplectic Euler: gather, v += a dt, x += v dt
//   velocity Verlet:  v += a dt/2, x += v dt | forces | gather, v += a dt/2
#include <omp.h>

#include <cmath>

#include "step_phases.hpp"

namespace runout::phases {

namespace {

// Sum of the contact forces and torques on disc k plus gravity, as accelerations (eqs.
// 2.10–2.11): its own row of pairs (k = i), then its incoming pairs (k = j, Newton's third
// law), then its walls, always in that order, so the sums do not depend on the thread count.
struct ForceSum {
  const double* pair_fx; const double* pair_fy;
  const double* torque_i; const double* torque_j;
  const std::int32_t* row_start; const std::int32_t* incoming_start; const std::int32_t* incoming;
  const double* wall_fx; const double* wall_fy; const double* wall_torque;
  const std::int32_t* wall_row_start;
  const double* inv_mass; const double* inv_inertia;
  double gx, gy;

  void operator()(std::int64_t k, double& ax, double& ay, double& alpha) const {
    double fx = 0, fy = 0, torque = 0;
    for (std::int32_t q = row_start[k]; q < row_start[k + 1]; ++q) {
      fx += pair_fx[q]; fy += pair_fy[q]; torque += torque_i[q];
    }
    for (std::int32_t e = incoming_start[k]; e < incoming_start[k + 1]; ++e) {
      const std::int32_t q = incoming[e];
      fx -= pair_fx[q]; fy -= pair_fy[q]; torque += torque_j[q];
    }
    for (std::int32_t q = wall_row_start[k]; q < wall_row_start[k + 1]; ++q) {
      fx += wall_fx[q]; fy += wall_fy[q]; torque += wall_torque[q];
    }
    ax = fx * inv_mass[k] + gx;
    ay = fy * inv_mass[k] + gy;
    alpha = torque * inv_inertia[k];
  }
};

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

Motion advance(const StepContext& step, Particles& p, const PairContacts& c,
               const WallContacts& w, const std::vector<double>& x_at_rebuild,
               const std::vector<double>& y_at_rebuild, bool gather, double kick, double drift) {
  const StepSettings& st = step.settings;
  const ForceSum sum{c.fx.data(), c.fy.data(), c.torque_i.data(), c.torque_j.data(),
                     c.row_start.data(), c.incoming_start.data(), c.incoming.data(),
                     w.fx.data(), w.fy.data(), w.torque.data(), w.row_start.data(),
                     p.inv_mass.data(), p.inv_inertia.data(), st.gravity.x(), st.gravity.y()};
  const double damping = st.local_damping;
  double* __restrict x = p.x.data(); double* __restrict y = p.y.data();
  double* __restrict vx = p.vx.data(); double* __restrict vy = p.vy.data();
  double* __restrict om = p.omega.data(); double* __restrict angle = p.angle.data();
  double* __restrict ax = p.ax.data(); double* __restrict ay = p.ay.data();
  double* __restrict alpha = p.alpha.data();
  const double* __restrict x0 = x_at_rebuild.data(); const double* __restrict y0 = y_at_rebuild.data();
  Motion part[kMaxThreads];
  for_blocks(static_cast<std::int64_t>(p.size()), st.threads,
             [&](std::int64_t lo, std::int64_t hi, int t) {
    // The sums first (scalar, data-dependent lengths), then the update as a plain loop the
    // compiler vectorises.
    if (gather) {
      for (std::int64_t k = lo; k < hi; ++k) sum(k, ax[k], ay[k], alpha[k]);
      if (damping > 0) damp(damping, lo, hi, ax, ay, alpha, vx, vy, om);
    }
    double max_d2 = 0;
    bool finite = true;
#pragma omp simd reduction(max : max_d2) reduction(&& : finite)
    for (std::int64_t k = lo; k < hi; ++k) {
      vx[k] += ax[k] * kick;
      vy[k] += ay[k] * kick;
      om[k] += alpha[k] * kick;
      x[k] += vx[k] * drift;
      y[k] += vy[k] * drift;
      angle[k] += om[k] * drift;
      const double ddx = x[k] - x0[k], ddy = y[k] - y0[k];
      max_d2 = std::max(max_d2, ddx * ddx + ddy * ddy);
      finite = finite && std::isfinite(x[k] + y[k] + vx[k] + vy[k] + om[k]);
    }
    part[t] = {max_d2, finite};
  });
  Motion total;
  for (int t = 0; t < st.threads; ++t) {
    total.max_displacement2 = std::max(total.max_displacement2, part[t].max_displacement2);
    total.finite = total.finite && part[t].finite;
  }
  return total;
}

}  // namespace runout::phases

// Contact laws: each is plain data (coefficients) plus a pure function of the overlap, its
// rate and the per-contact history. This header is the place to start reading runout: the pair
// loop in pair_forces.cpp is written once and takes a normal law as a template argument.
//
// Sign conventions (SPEC §2): for a pair (i, j) the unit normal n points from i to j,
// s = (-n_y, n_x); overlap = r_i + r_j - |x_j - x_i| (eq. 2.1); overlap_rate = d(overlap)/dt.
// A wall takes the place of j with zero velocity and zero radius behind the contact point.
#pragma once

#include <algorithm>
#include <cmath>

namespace runout {

// ---- Normal laws ------------------------------------------------------------------------

// Walton–Braun hysteretic linear spring (thesis eqs. 2.3–2.4). Loading follows k_load * overlap;
// unloading and re-loading follow k_unload * (overlap - overlap_0) with
// overlap_0 = overlap_max (1 - k_load / k_unload), capped by the loading line, never tensile.
// Energy returned on unloading is k_load / k_unload = e_n^2 of the energy stored, so an isolated
// binary collision has restitution exactly e_n.
struct WaltonBraun {
  struct Coefficients {
    double k_load = 0;    // k_L
    double k_unload = 0;  // k_U = k_L / e_n^2
  };
  static constexpr bool has_history = true;  // keeps overlap_max per contact

  // `overlap_max` is the contact's largest overlap so far; updated in place.
  static double force(const Coefficients& c, double overlap, double /*overlap_rate*/,
                      double& overlap_max) {
    overlap_max = std::max(overlap_max, overlap);
    const double unloading = c.k_unload * overlap - (c.k_unload - c.k_load) * overlap_max;
    return std::max(0.0, std::min(c.k_load * overlap, unloading));
  }
  // Energy ledger: the spring energy held now, and the loss already committed by having
  // reached overlap_max (area between the loading and unloading lines).
  static double elastic_energy(const Coefficients& c, double overlap, double overlap_max) {
    if (overlap >= overlap_max) return 0.5 * c.k_load * overlap * overlap;
    const double stretch = std::max(0.0, overlap - overlap_max * (1.0 - c.k_load / c.k_unload));
    return 0.5 * c.k_unload * stretch * stretch;
  }
  static double committed_loss(const Coefficients& c, double overlap_max) {
    return 0.5 * c.k_load * overlap_max * overlap_max * (1.0 - c.k_load / c.k_unload);
  }
  // Power lost in a dashpot (none: the loss is the hysteresis above).
  static double dashpot_power(const Coefficients&, double, double) { return 0.0; }
};

// Linear spring–dashpot with the no-tension cut: F = k overlap + damping * overlap_rate, F >= 0.
// damping = c_e sqrt(m* k) with c_e solved for e_n with the cut in place (derive.cpp): the
// textbook zeta = -ln e / sqrt(pi^2 + ln^2 e) ignores the cut and gives 0.32 for e_n = 0.2.
struct LinearDashpot {
  struct Coefficients {
    double k = 0;
    double damping = 0;
  };
  static constexpr bool has_history = false;
  static double force(const Coefficients& c, double overlap, double overlap_rate, double&) {
    return std::max(0.0, c.k * overlap + c.damping * overlap_rate);
  }
  static double elastic_energy(const Coefficients& c, double overlap, double) {
    return 0.5 * c.k * overlap * overlap;
  }
  static double committed_loss(const Coefficients&, double) { return 0.0; }
  // Power lost: the force's power on the contact minus the spring's, (F - k overlap) rate.
  // That is damping * rate^2 while the force is positive, and the spring's own energy while the
  // no-tension cut holds the force at zero during unloading (nothing gives it back).
  static double dashpot_power(const Coefficients& c, double overlap, double overlap_rate) {
    const double f = std::max(0.0, c.k * overlap + c.damping * overlap_rate);
    return (f - c.k * overlap) * overlap_rate;
  }
};

// Hertz with a non-linear dashpot: F = k overlap^{3/2} + damping overlap^{1/4} overlap_rate,
// F >= 0. With damping = c_e sqrt(m* k) the restitution depends on c_e only, so c_e is solved
// once per e_n (derive.cpp, hertz_damping_for_restitution) and e_n is hit exactly.
struct Hertz {
  struct Coefficients {
    double k = 0;
    double damping = 0;
  };
  static constexpr bool has_history = false;
  static double force(const Coefficients& c, double overlap, double overlap_rate, double&) {
    const double root = std::sqrt(std::max(overlap, 0.0));
    return std::max(0.0, c.k * overlap * root + c.damping * std::sqrt(root) * overlap_rate);
  }
  static double elastic_energy(const Coefficients& c, double overlap, double) {
    const double o = std::max(overlap, 0.0);
    return 0.4 * c.k * o * o * std::sqrt(o);
  }
  static double committed_loss(const Coefficients&, double) { return 0.0; }
  static double dashpot_power(const Coefficients& c, double overlap, double overlap_rate) {
    const double root = std::sqrt(std::max(overlap, 0.0));
    const double spring = c.k * overlap * root;
    const double f = std::max(0.0, spring + c.damping * std::sqrt(root) * overlap_rate);
    return (f - spring) * overlap_rate;  // as for LinearDashpot
  }
};

// ---- Tangential law ---------------------------------------------------------------------

// Cundall–Strack spring in series with a Coulomb slider (thesis eqs. 2.5–2.8). The spring
// stretch `tangential_spring` is contact history: it accumulates the tangential displacement of
// j relative to i at the contact point; when |k_s spring| exceeds mu F_n the contact slides and
// the stretch is clipped to mu F_n / k_s. Returns the tangential force on i along s
// (the force on j is its negative).
struct CundallStrack {
  double k_tangential = 0;  // k_s
  double friction = 0;      // mu
};

inline double tangential_force(const CundallStrack& c, double normal_force,
                               double tangential_step, double& tangential_spring) {
  const double trial = tangential_spring + tangential_step;
  const double limit = c.friction * normal_force / c.k_tangential;
  tangential_spring = std::max(-limit, std::min(trial, limit));
  return c.k_tangential * tangential_spring;
}

}  // namespace runout

// Hertz with a non-linear dashpot: F = k overlap^{3/2} + damping overlap^{1/4} overlap_rate,
// F >= 0. With damping = c_e sqrt(m* k) the restitution depends on c_e only, so c_e is solved
// once per e_n (derive.cpp, dashpot_design) and e_n is hit exactly.
#pragma once

#include <algorithm>
#include <cmath>

#include "runout/contact/contact.hpp"

namespace runout {

struct Hertz {
  static constexpr const char* kName = "hertz";
  static constexpr int kHistory = 0;
  struct Params {
    double k = 0;
    double damping = 0;
  };
  // Stiffness such that the design impact speed gives the design peak overlap.
  static double stiffness(const PairCoefficients& c) {
    return c.reduced_mass * c.design_speed * c.design_speed *
           std::pow(c.dashpot.peak_overlap / c.design_overlap, 2.5);
  }
  static Params params(const PairCoefficients& c) {
    const double k = stiffness(c);
    return {k, c.dashpot.damping_constant * std::sqrt(c.reduced_mass * k)};
  }
  static DashpotDesign design(double restitution) { return dashpot_design(restitution, true); }
  // The tangent stiffness at the design overlap.
  static double stiffness_for_dt(const PairCoefficients& c) {
    return 1.5 * stiffness(c) * std::sqrt(c.design_overlap);
  }

  static double force(const Params& p, const ContactKinematics& k, double*, double& loss) {
    const double root = std::sqrt(std::max(k.overlap, 0.0));
    const double spring = p.k * k.overlap * root;
    const double f = std::max(0.0, spring + p.damping * std::sqrt(root) * k.overlap_rate);
    loss += (f - spring) * k.overlap_rate * k.dt;  // as for LinearDashpot
    return f;
  }
  static double elastic_energy(const Params& p, double overlap, const double*) {
    const double o = std::max(overlap, 0.0);
    return 0.4 * p.k * o * o * std::sqrt(o);
  }
  static double committed_loss(const Params&, const double*) { return 0.0; }
};

}  // namespace runout

// Linear spring–dashpot with the no-tension cut: F = k overlap + damping overlap_rate, F >= 0.
// damping = c_e sqrt(m* k) with c_e solved for e_n with the cut in place (derive.cpp): the
// textbook zeta = -ln e / sqrt(pi^2 + ln^2 e) ignores the cut and gives 0.32 for e_n = 0.2.
#pragma once

#include <algorithm>
#include <cmath>

#include "runout/contact/contact.hpp"

namespace runout {

struct LinearDashpot {
  static constexpr const char* kName = "linear_dashpot";
  static constexpr int kHistory = 0;
  struct Params {
    double k = 0;
    double damping = 0;
  };
  // The design stiffness itself, damping for e_n with the no-tension cut.
  static Params params(const PairCoefficients& c) {
    return {c.k_unload, c.dashpot.damping_constant * std::sqrt(c.reduced_mass * c.k_unload)};
  }
  static DashpotDesign design(double restitution) { return dashpot_design(restitution, false); }
  static double stiffness_for_dt(const PairCoefficients& c) { return c.k_unload; }

  // The loss is the force's power on the contact minus the spring's, (F - k overlap) rate:
  // damping rate^2 while F > 0, and the spring's own energy while the cut holds F at zero
  // during unloading (nothing gives it back).
  static double force(const Params& p, const ContactKinematics& k, double*, double& loss) {
    const double f = std::max(0.0, p.k * k.overlap + p.damping * k.overlap_rate);
    loss += (f - p.k * k.overlap) * k.overlap_rate * k.dt;
    return f;
  }
  static double elastic_energy(const Params& p, double overlap, const double*) {
    return 0.5 * p.k * overlap * overlap;
  }
  static double committed_loss(const Params&, const double*) { return 0.0; }
};

}  // namespace runout

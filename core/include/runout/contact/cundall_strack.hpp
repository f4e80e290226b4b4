// Cundall–Strack spring in series with a Coulomb slider (thesis eqs. 2.5–2.8, SPEC §2): the
// seed's tangential law. The spring stretch is contact history: it accumulates the tangential
// displacement of j relative to i at the contact point; when |k_s stretch| exceeds mu F_n the
// contact slides and the stretch is clipped to mu F_n / k_s. The force is on i along s.
#pragma once

#include <algorithm>
#include <cmath>

#include "runout/contact/contact.hpp"

namespace runout {

struct CundallStrack {
  static constexpr const char* kName = "cundall_strack";
  static constexpr int kHistory = 1;  // the spring's stretch (m)
  struct Params {
    double k_tangential = 0;  // k_s
    double friction = 0;      // mu
  };
  static Params params(const PairCoefficients& c) { return {c.k_tangential, c.friction}; }
  static double stiffness_for_dt(const PairCoefficients& c) { return c.k_tangential; }

  // Sliding loses |F_t| times the slip the spring did not take.
  static double force(const Params& p, const ContactKinematics& k, double normal_force,
                      double* history, double& loss) {
    double& stretch = history[0];
    const double trial = stretch + k.slip * k.dt;
    const double limit = p.friction * normal_force / p.k_tangential;
    stretch = std::max(-limit, std::min(trial, limit));
    const double f = p.k_tangential * stretch;
    loss += std::abs(f * (trial - stretch));
    return f;
  }
  static double elastic_energy(const Params& p, const ContactKinematics&, const double* history) {
    return 0.5 * p.k_tangential * history[0] * history[0];
  }
};

}  // namespace runout

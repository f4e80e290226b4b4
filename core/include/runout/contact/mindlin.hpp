// Mindlin's no-slip tangential spring with a Coulomb cap, for the Hertz normal law (Mindlin
// 1949; the "Hertz–Mindlin no-slip" model of Chung & Ooi 2011 and LAMMPS `tangential
// mindlin`). The tangential stiffness follows the contact radius a ~ sqrt(overlap), as Hertz's
// normal tangent stiffness does: k_t = kratio (dF_n / d overlap) = kratio 1.5 k_hertz
// sqrt(overlap), with kratio = 2 (1 - nu) / (2 - nu) for a material of Poisson's ratio nu
// (8 G* a over 2 E* a). History is the tangential displacement u; the force k_t(a) u follows
// the area as it grows and shrinks. tests/test_mindlin.cpp holds this against Chung & Ooi's
// test 4; storing the force instead (F += k_t du) or also shrinking u with a on unloading
// (LAMMPS's mindlin_rescale) misses their 5-degree point by 0.09 and 0.06.
#pragma once

#include <algorithm>
#include <cmath>

#include "runout/contact/contact.hpp"
#include "runout/contact/hertz.hpp"

namespace runout {

struct Mindlin {
  static constexpr const char* kName = "mindlin";
  static constexpr const char* kNormalLaw = "hertz";
  static constexpr int kHistory = 1;  // tangential displacement u (m)
  struct Params {
    double k_root = 0;    // k_t / sqrt(overlap), N/m^1.5
    double friction = 0;  // mu
  };
  static Params params(const PairCoefficients& c) {
    return {c.stiffness_ratio * 1.5 * Hertz::stiffness(c), c.friction};
  }
  // Its stiffness at the design overlap (where Hertz's tangent stiffness is taken for tau_min).
  static double stiffness_for_dt(const PairCoefficients& c) {
    return c.stiffness_ratio * c.normal_stiffness_for_dt;
  }

  // Coulomb: |k_t u| <= mu F_n; the slip the spring cannot take is sliding, and loses
  // |F_t| times that slip. A contact without area (k_t = 0) holds no displacement.
  static double force(const Params& p, const ContactKinematics& k, double normal_force,
                      double* history, double& loss) {
    double& displacement = history[0];
    const double k_t = p.k_root * std::sqrt(std::max(k.overlap, 0.0));
    const double trial = displacement + k.slip * k.dt;
    const double limit = k_t > 0 ? p.friction * normal_force / k_t : 0.0;
    displacement = std::max(-limit, std::min(trial, limit));
    const double f = k_t * displacement;
    loss += std::abs(f * (trial - displacement));
    return f;
  }
  static double elastic_energy(const Params& p, const ContactKinematics& k, const double* history) {
    const double k_t = p.k_root * std::sqrt(std::max(k.overlap, 0.0));
    return 0.5 * k_t * history[0] * history[0];
  }
};

}  // namespace runout

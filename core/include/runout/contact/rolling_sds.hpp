// Rolling resistance of the elastic–plastic spring–dashpot kind (Ai, Chen, Rotter & Ooi 2011,
// model type C; LAMMPS `rolling sds`, MercuryDPM's rolling friction). A torque resists the
// relative rolling of the two surfaces, omega_i - omega_j (a wall: omega_i):
//   spring   M_k <- M_k - k_r (omega_i - omega_j) dt, held to |M_k| <= mu_r r* F_n (plastic);
//   dashpot  M_d = -C_r (omega_i - omega_j) while the spring holds, none while it yields.
// k_r = 2.25 k_n mu_r^2 r*^2 (Ai et al., from Iwashita & Oda) with k_n the normal law's
// stiffness, and C_r = eta_r 2 sqrt(I_r k_r), I_r = 1.4 m* r*^2 the rolling inertia about the
// contact point (7/5 m r^2 of a disc with sphere inertia on a plane). A disc on an incline is
// held when tan(theta) <= mu_r; a rolling one decelerates at 5/7 mu_r g (tests/test_rolling.cpp).
#pragma once

#include <algorithm>
#include <cmath>

#include "runout/contact/contact.hpp"

namespace runout {

struct RollingSpringDashpot {
  static constexpr const char* kName = "sds";
  static constexpr int kHistory = 1;  // the spring's torque on i (N m)
  struct Params {
    double k_roll = 0;      // k_r, N m / rad
    double damping = 0;     // C_r, N m s / rad
    double lever = 0;       // mu_r r*, m: the plastic limit is lever * F_n
  };
  static Params params(const PairCoefficients& c) {
    const double r = c.reduced_radius, mu_r = c.rolling_friction;
    const double k_r = 2.25 * c.normal_stiffness_for_dt * mu_r * mu_r * r * r;
    const double inertia = 1.4 * c.reduced_mass * r * r;
    return {k_r, c.rolling_damping * 2 * std::sqrt(inertia * k_r), mu_r * r};
  }

  // The torque on i (on j it is the opposite). Losses, by the spring's energy balance over
  // the step: the bodies turn against the spring's new torque, -M_k rate dt, less what the
  // spring now holds more, (M_k^2 - M_old^2) / 2 k_r. That is the plastic rotation times the
  // limit while it yields, and also the energy a falling limit releases when F_n drops; plus
  // the dashpot's power while the spring holds.
  static double torque(const Params& p, const ContactKinematics& k, double normal_force,
                       double* history, double& loss) {
    double& spring = history[0];
    const double before = spring, rate = k.spin_difference;
    const double trial = spring - p.k_roll * rate * k.dt;
    const double limit = p.lever * normal_force;
    spring = std::max(-limit, std::min(trial, limit));
    const bool holds = spring == trial;
    const double dashpot = holds ? -p.damping * rate : 0.0;
    const double released = p.k_roll > 0 ? -spring * rate * k.dt -
                                                0.5 * (spring * spring - before * before) / p.k_roll
                                          : 0.0;
    loss += (holds ? 0.0 : released) + (holds ? p.damping * rate * rate * k.dt : 0.0);
    return spring + dashpot;
  }
  static double elastic_energy(const Params& p, const ContactKinematics&, const double* history) {
    return p.k_roll > 0 ? 0.5 * history[0] * history[0] / p.k_roll : 0.0;
  }
};

}  // namespace runout

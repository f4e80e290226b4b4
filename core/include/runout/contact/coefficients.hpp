// The knobs of one interaction (species a with species b, or species a with a wall) after
// SPEC §3's design: every law derives its own Params from these (contact.hpp).
#pragma once

namespace runout {

// Dashpot constant c_e (damping = c_e sqrt(m* k)) that gives restitution e_n with the
// no-tension cut, and the peak overlap in units of (m* v^2 / k)^{2/5} (Hertz) or v sqrt(m*/k)
// (linear). Solved once per restitution for the chosen normal law (derive.cpp).
struct DashpotDesign {
  double damping_constant = 0;
  double peak_overlap = 0;
};

// Solved by bisection on x'' = -max(0, x^{3/2} + c_e x^{1/4} x') (Hertz) or -max(0, x + c_e x')
// (linear), derive.cpp.
DashpotDesign dashpot_design(double restitution, bool hertz);

struct PairCoefficients {
  double reduced_radius = 0;  // r* = r_a r_b / (r_a + r_b); wall: r_a
  double reduced_mass = 0;    // m* likewise
  double k_unload = 0;        // k_U: the design stiffness of SPEC §3
  double k_load = 0;          // k_L = e_n^2 k_U
  double design_speed = 0;    // m/s: the impact speed the stiffness is designed for
  double design_overlap = 0;  // m: the peak overlap allowed at that speed
  DashpotDesign dashpot;      // of the chosen normal law, for this pair's e_n
  double k_tangential = 0;    // k_s = kratio k_L (Cundall–Strack)
  double stiffness_ratio = 0; // kratio: tangential over normal stiffness
  double friction = 0;        // Coulomb mu
  double rolling_friction = 0;  // mu_r: rolling torque limit over r* F_n
  double rolling_damping = 0;   // eta_r: rolling dashpot over its critical value
  // k_n and k_t entering tau_min (SPEC §3) for the chosen normal and tangential laws.
  double normal_stiffness_for_dt = 0, tangential_stiffness_for_dt = 0;
};

}  // namespace runout

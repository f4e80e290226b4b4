// Walton–Braun hysteretic linear spring (thesis eqs. 2.3–2.4, SPEC §2): the seed's normal law.
// Loading follows k_L overlap; unloading and re-loading follow k_U (overlap - overlap_0) with
// overlap_0 = overlap_max (1 - k_L / k_U), capped by the loading line, never tensile. Energy
// returned on unloading is k_L / k_U = e_n^2 of the energy stored, so an isolated binary
// collision has restitution exactly e_n.
#pragma once

#include <algorithm>

#include "runout/contact/contact.hpp"

namespace runout {

struct WaltonBraun {
  static constexpr const char* kName = "walton_braun";
  static constexpr int kHistory = 1;  // overlap_max: the contact's largest overlap so far
  struct Params {
    double k_load = 0;    // k_L
    double k_unload = 0;  // k_U = k_L / e_n^2
  };
  static Params params(const PairCoefficients& c) { return {c.k_load, c.k_unload}; }
  static DashpotDesign design(double) { return {}; }
  static double stiffness_for_dt(const PairCoefficients& c) { return c.k_unload; }

  static double force(const Params& p, const ContactKinematics& k, double* history, double&) {
    double& overlap_max = history[0];
    overlap_max = std::max(overlap_max, k.overlap);
    const double unloading = p.k_unload * k.overlap - (p.k_unload - p.k_load) * overlap_max;
    return std::max(0.0, std::min(p.k_load * k.overlap, unloading));
  }
  // The spring energy held now; the loss is committed by having reached overlap_max (the area
  // between the loading and unloading lines) and booked when the contact ends.
  static double elastic_energy(const Params& p, double overlap, const double* history) {
    const double overlap_max = history[0];
    if (overlap >= overlap_max) return 0.5 * p.k_load * overlap * overlap;
    const double stretch = std::max(0.0, overlap - overlap_max * (1.0 - p.k_load / p.k_unload));
    return 0.5 * p.k_unload * stretch * stretch;
  }
  static double committed_loss(const Params& p, const double* history) {
    const double overlap_max = history[0];
    return 0.5 * p.k_load * overlap_max * overlap_max * (1.0 - p.k_load / p.k_unload);
  }
};

}  // namespace runout

// What every contact law sees and returns, and how the laws of one contact are put together
// (the LAMMPS GRANULAR / HOOMD habit, ../shared/STYLE.md): a contact model is a normal law, a
// tangential law and a rolling law, each a small struct with
//   Params                  derived once per species pair and wall from PairCoefficients
//   kHistory                how many doubles of per-contact history it keeps
//   a pure evaluate         kinematics + params + its history -> its share of force/torque
//   energy terms            for the ledger (SPEC §8)
// and one registry row (registry.hpp). The kernel (core/src/contact_forces.cpp) runs the same
// code for disc–disc pairs and disc–wall contacts: a wall is a body j with zero velocity, zero
// spin and zero radius behind the contact point.
//
// Sign conventions (SPEC §2): the unit normal n points from i to j, s = (-n_y, n_x);
// overlap = r_i + r_j - |x_j - x_i| (eq. 2.1); overlap_rate = d(overlap)/dt.
#pragma once

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "runout/contact/coefficients.hpp"

namespace runout {

// The relative motion of one contact this step.
struct ContactKinematics {
  double overlap = 0, overlap_rate = 0;
  // Tangential velocity of j relative to i at the contact point, along s (eq. 2.7).
  double slip = 0;
  // omega_i - omega_j (a wall: omega_i): the relative rolling of the two surfaces.
  double spin_difference = 0;
  double radius_i = 0, radius_j = 0;  // lever arms; a wall has radius_j = 0
  double dt = 0;
};

// Energy lost this step by one contact (J), by mechanism (the ledger's columns).
struct ContactLoss {
  double normal = 0, friction = 0, rolling = 0;
};

// What a contact does to its two bodies this step: the normal force (pushing them apart), the
// tangential force on i along s (on j: the opposite), and the torque on each.
struct ContactAction {
  double normal = 0, tangential = 0;
  double torque_i = 0, torque_j = 0;
};

// No tangential force: chosen automatically when mu = 0 for every contact, so no spring is
// stored, read or written (SPEC §2 with mu = 0).
struct Frictionless {
  static constexpr const char* kName = "none";
  static constexpr int kHistory = 0;
  struct Params {};
  static Params params(const PairCoefficients&) { return {}; }
  static double force(const Params&, const ContactKinematics&, double, double*, double&) { return 0; }
  static double elastic_energy(const Params&, const ContactKinematics&, const double*) { return 0; }
};

// No rolling resistance: the only torque is the tangential force's, r F_t.
struct NoRolling {
  static constexpr const char* kName = "none";
  static constexpr int kHistory = 0;
  struct Params {};
  static Params params(const PairCoefficients&) { return {}; }
  static double torque(const Params&, const ContactKinematics&, double, double*, double&) { return 0; }
  static double elastic_energy(const Params&, const ContactKinematics&, const double*) { return 0; }
};

// One contact's laws together. History is laid out normal | tangential | rolling.
template <class Normal, class Tangential, class Rolling>
struct ContactModel {
  using NormalLaw = Normal;
  using TangentialLaw = Tangential;
  using RollingLaw = Rolling;
  static constexpr int kHistory = Normal::kHistory + Tangential::kHistory + Rolling::kHistory;
  static constexpr bool kFriction = !std::is_same_v<Tangential, Frictionless>;
  static constexpr bool kRolling = !std::is_same_v<Rolling, NoRolling>;

  struct Params {
    typename Normal::Params normal;
    typename Tangential::Params tangential;
    typename Rolling::Params rolling;
  };
  static Params params(const PairCoefficients& c) {
    return {Normal::params(c), Tangential::params(c), Rolling::params(c)};
  }

  // `history` holds this contact's state before the step and is updated in place; `loss`
  // gets what the laws dissipated (for a contact that touches; the kernel books ending ones).
  static ContactAction evaluate(const Params& p, const ContactKinematics& k, double* history,
                                ContactLoss& loss) {
    ContactAction a;
    a.normal = Normal::force(p.normal, k, history, loss.normal);
    a.tangential = Tangential::force(p.tangential, k, a.normal, history + Normal::kHistory,
                                     loss.friction);
    // The tangential force at the surface of each body: torque r F_t, same sign on both.
    a.torque_i = k.radius_i * a.tangential;
    a.torque_j = k.radius_j * a.tangential;
    if constexpr (kRolling) {
      const double m = Rolling::torque(p.rolling, k, a.normal,
                                       history + Normal::kHistory + Tangential::kHistory,
                                       loss.rolling);
      a.torque_i += m;
      a.torque_j -= m;
    }
    return a;
  }
  // Spring energy held by a touching contact now (SPEC §8).
  static double elastic_energy(const Params& p, const ContactKinematics& k, const double* history) {
    return Normal::elastic_energy(p.normal, k.overlap, history) +
           Tangential::elastic_energy(p.tangential, k, history + Normal::kHistory) +
           Rolling::elastic_energy(p.rolling, k, history + Normal::kHistory + Tangential::kHistory);
  }
  // Loss already committed by the history (Walton–Braun's hysteresis), booked when it ends.
  static double committed_loss(const Params& p, const double* history) {
    return Normal::committed_loss(p.normal, history);
  }
};

}  // namespace runout

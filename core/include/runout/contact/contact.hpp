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
#include <cstdint>
#include <type_traits>
#include <vector>

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

// One contact's laws together. History columns are laid out normal | tangential | rolling.
template <class Normal, class Tangential, class Rolling>
struct ContactModel {
  using NormalLaw = Normal;
  using TangentialLaw = Tangential;
  using RollingLaw = Rolling;
  static constexpr int kHistory = Normal::kHistory + Tangential::kHistory + Rolling::kHistory;
  static constexpr bool kFriction = !std::is_same_v<Tangential, Frictionless>;
  static constexpr bool kRolling = !std::is_same_v<Rolling, NoRolling>;

  // Each law's Params in its own table (one row per species pair or wall): gathering a
  // field from a small struct by the pair's kind is what the vectoriser does well.
  struct Tables {
    std::vector<typename Normal::Params> normal;
    std::vector<typename Tangential::Params> tangential;
    std::vector<typename Rolling::Params> rolling;
  };
  static Tables tables(const std::vector<PairCoefficients>& rows) {
    Tables t;  // built once per World (phases::derive_laws)
    t.normal.reserve(rows.size());
    t.tangential.reserve(rows.size());
    t.rolling.reserve(rows.size());
    for (const auto& c : rows) {
      t.normal.push_back(Normal::params(c));
      t.tangential.push_back(Tangential::params(c));
      t.rolling.push_back(Rolling::params(c));
    }
    return t;
  }
  // Raw pointers into Tables, indexed by the contact's kind.
  struct Row {
    const typename Normal::Params* __restrict normal;
    const typename Tangential::Params* __restrict tangential;
    const typename Rolling::Params* __restrict rolling;
  };
  static Row row(const Tables& t) { return {t.normal.data(), t.tangential.data(), t.rolling.data()}; }

  // `history` holds this contact's state before the step and is updated in place; `loss`
  // gets what the laws dissipated (for a contact that touches; the kernel books ending ones).
  static ContactAction evaluate(const Row& p, std::int32_t kind, const ContactKinematics& k,
                                double* history, ContactLoss& loss) {
    ContactAction a;
    a.normal = Normal::force(p.normal[kind], k, history, loss.normal);
    a.tangential = Tangential::force(p.tangential[kind], k, a.normal,
                                     history + Normal::kHistory, loss.friction);
    // The tangential force at the surface of each body: torque r F_t, same sign on both.
    a.torque_i = k.radius_i * a.tangential;
    a.torque_j = k.radius_j * a.tangential;
    if constexpr (kRolling) {
      const double m = Rolling::torque(p.rolling[kind], k, a.normal,
                                       history + Normal::kHistory + Tangential::kHistory,
                                       loss.rolling);
      a.torque_i += m;
      a.torque_j -= m;
    }
    return a;
  }
  // Spring energy held by a touching contact now (SPEC §8).
  static double elastic_energy(const Row& p, std::int32_t kind, const ContactKinematics& k,
                               const double* history) {
    return Normal::elastic_energy(p.normal[kind], k.overlap, history) +
           Tangential::elastic_energy(p.tangential[kind], k, history + Normal::kHistory) +
           Rolling::elastic_energy(p.rolling[kind], k,
                                   history + Normal::kHistory + Tangential::kHistory);
  }
  // Loss already committed by the history (Walton–Braun's hysteresis), booked when it ends.
  static double committed_loss(const Row& p, std::int32_t kind, const double* history) {
    return Normal::committed_loss(p.normal[kind], history);
  }
};

}  // namespace runout

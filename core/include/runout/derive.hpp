// Parameters derived from the user's knobs (SPEC §3): stiffnesses per species pair and per
// species–wall pair, the time step, and the unit of time.
#pragma once

#include <span>
#include <vector>

#include "runout/contact/coefficients.hpp"
#include "runout/scene.hpp"

namespace runout {

inline constexpr double kPi = 3.14159265358979323846;

// Every coefficient the step loop needs, indexed by species (row-major a * n + b).
struct ContactTable {
  int species_count = 0;
  std::vector<PairCoefficients> pair;  // species_count^2, symmetric
  std::vector<PairCoefficients> wall;  // species_count
  const PairCoefficients& between(int a, int b) const { return pair[a * species_count + b]; }
  // Whether any contact has a Coulomb slider: with mu = 0 everywhere the tangential force is
  // zero, so no tangential spring is kept or computed (SPEC §2 with mu = 0).
  bool frictional() const {
    for (const auto& c : pair) if (c.friction > 0) return true;
    for (const auto& c : wall) if (c.friction > 0) return true;
    return false;
  }
};

// f = exp(-atan(beta)/beta), beta = pi / ln(e_n): peak overlap of a damped linear oscillator in
// units of v / omega_0 (SPEC §3); 0.56997 for e_n = 0.2, 1 for e_n = 1.
double peak_overlap_factor(double restitution);

double sphere_mass(double radius, double density);      // 4/3 pi r^3 rho (eq. 2.12)
double sphere_inertia(double mass, double radius);      // 2/5 m r^2 (eq. 2.13)

ContactTable derive_contact_table(const MaterialDef& material, const ContactDef& contact,
                                  std::span<const SpeciesDef> species, double gravity);

// The translational and rotational periods of the smallest disc of species a in a ring of its
// neighbours of species b (b < 0: a wall, as stiff as a ring of 6), SPEC §3: N_surr = 6 for
// equal discs, more around a large disc.
struct CollisionPeriods {
  double translational = 0, rotational = 0;
  double ring = 0;  // N_surr
};
CollisionPeriods collision_periods(const ContactTable& table, std::span<const SpeciesDef> species,
                                   double density, int a, int b);

// tau_min over the pairs of species present and their walls (collision_periods).
double minimum_collision_period(const ContactTable& table, std::span<const SpeciesDef> species,
                                double density, const std::vector<char>& present);

// The unit of length is the smallest nominal diameter d; one t* is sqrt(d/g) seconds.
double unit_length(std::span<const SpeciesDef> species);
double unit_time(std::span<const SpeciesDef> species, double gravity);

}  // namespace runout

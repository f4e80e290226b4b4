// Plain definition structs for a scene, with units and defaults (SPEC §3, §5). The TOML reader
// (io/) fills them at the edge; the core never parses text. Lengths are metres unless a
// name says otherwise; every time a user gives or sees is t* = t sqrt(g/d) (SPEC §4).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace runout {

enum class IntegratorKind { symplectic_euler, velocity_verlet };

struct MaterialDef {
  double density = 2500.0;        // kg/m^3 (thesis §3.1.1)
  double friction = 0.5;          // particle–particle Coulomb mu
  double wall_friction = 0.5;     // particle–wall mu
  double restitution = 0.2;       // particle–particle e_n
  double wall_restitution = 0.2;  // particle–wall e_n
};

// The user's stiffness knobs; k_L, k_U, k_s are derived from them (SPEC §3).
struct ContactDef {
  // The contact laws by name (contact/registry.hpp lists them).
  std::string normal_model = "walton_braun";
  std::string tangential_model = "cundall_strack";
  std::string rolling_model = "none";
  double design_impact_speed = 10.0;  // alphadot0, units of sqrt(g r*)
  double design_max_overlap = 0.01;   // alphamax, fraction of r*
  double stiffness_ratio = 1.0;       // kratio = k_s / k_L
  double rolling_friction = 0.0;      // mu_r: rolling torque limit over r* F_n (rolling laws)
  double rolling_damping = 0.3;       // eta_r: rolling dashpot over its critical value
  // Stop when an impact overlaps beyond this share of the depth at which its contact would be
  // passed through (world.hpp): 0.75 is an overlap of 1.5 radii between equal discs.
  double overlap_guard = 0.75;
};

struct IntegrationDef {
  IntegratorKind integrator = IntegratorKind::symplectic_euler;
  double dt_fraction = 0.1;  // dt = dt_fraction * tau_min (SPEC §3); at most 1/pi (stability)
  double skin = 0.2;         // Verlet skin in small diameters d (SPEC §5 contact search)
  double gravity = 9.81;     // m/s^2
};

// How a species' diameters are drawn: the thesis's spread about a nominal diameter, or one
// class of a continuous size distribution by area (polydisperse piles, size_distribution.hpp).
enum class SizeDistribution { spread, uniform, lognormal };

struct SpeciesDef {
  std::string name;
  double diameter = 0;     // nominal, m: stiffness and counts are designed for it
  double spread = 0.1;     // spread: each diameter uniform in nominal * [1 - spread, 1 + spread]
  double area_share = 0;   // share of the total disc area (avalanche scenes)
  // A class of a distribution by area: its diameters lie in [min_diameter, max_diameter]
  // (nominal: their geometric mean); lognormal: ln d is normal by area, median and sigma.
  SizeDistribution distribution = SizeDistribution::spread;
  double min_diameter = 0, max_diameter = 0;
  double median = 0, sigma = 0;
};

// Which side of a wall the discs are on, seen along the polyline from its first point: a
// one-sided wall bounds a container (a disc pressed past its line is still pushed back to
// that side, so none passes through); `both` is a thin plate that pushes a disc to whichever
// side its centre is on (walls.hpp).
enum class WallInside { both, left, right };

// One straight rigid wall or a polyline of them (walls.hpp says how vertices act).
struct WallDef {
  std::string name;
  std::vector<std::pair<double, double>> points;  // at least two
  bool bed = false;        // counts as the bed for heights above bed and basal spin (SPEC §6)
  WallInside inside = WallInside::both;
};

struct ParticleDef {
  double x = 0, y = 0, vx = 0, vy = 0, omega = 0;
  double diameter = 0;
  int species = 0;  // index into SceneDef::species
};

// The thesis geometry of SPEC §5. x = 0 at the foot of the incline, y = 0 on the floor.
struct AvalancheDef {
  double incline_angle_deg = 30.0;
  double incline_length = 50.0;   // along the incline from the gate to the foot, in large diameters D
  double pile_width = 20.0;       // horizontal distance back wall to gate, in D
  double floor_length = 250.0;    // from the foot, in D; an end wall closes it
  double wall_height = 60.0;      // back wall, gate and end wall height above their foot, in D
  int reference_large_count = 500;  // N0: total disc area = area of N0 large discs (SPEC §5)
};

struct PreparationDef {
  std::uint64_t seed = 1;
  double initial_packing = 0.45;  // disc area / box area when the centres are placed
  double initial_speed = 1.0;     // random velocities uniform in +-initial_speed sqrt(g d)
  double growth_time = 0.5;       // t*, e-folding time of the exponential radius growth
  double settle_ek_threshold = 1e-7;  // settled when E_k/Ep < this ...
  double settle_hold = 1.0;           // ... for this long (t*), after growth is done
  double settle_max_time = 200.0;     // t*; not settled by then is an error
  // PFC local damping while the pile grows and settles (none in the flow); 0 settles undamped.
  double damping = 0.7;
};

struct RestDef {
  double ek_threshold = 1e-5;  // at rest when E_k/Ep0 < this ...
  double hold = 5.0;           // ... continuously for this long (t*)
  double max_time = 2000.0;    // t*; not at rest by then ends the run as not at rest
};

// The analysis series a run computes and writes (timeseries.csv, the summary's ledger). Those
// not selected are never computed: no dissipation counters in the pair pass without `energy`,
// no bed distances without `segregation`, and so on. t*, E_k, E_rot and the centre of mass are
// always there (the rest criterion and mu need them).
struct SeriesSelection {
  bool energy = true;       // the energy ledger (SPEC §8)
  bool segregation = true;  // mean heights of small and large discs above the bed (SPEC §6)
  bool basal_spin = true;   // of the small discs touching the bed (SPEC §6)
  bool front = true;        // farthest disc edge
  bool overlap = true;      // largest overlap / smaller radius among touching pairs
};

struct OutputDef {
  SeriesSelection series;
  double timeseries_every = 0.5;  // t*
  double checkpoint_every = 50.0; // t*; 0 disables periodic checkpoints
  double dump_every = 0.0;        // t*; 0 disables LAMMPS dump frames
  double vtk_every = 0.0;         // t*; 0 disables VTK frames (ParaView)
  double end_time = 0.0;          // t*; > 0 stops the run there even if not at rest
  double basal_layer_packing = 0.7;  // C in H_layer = pi sum r^2 / (L C) (SPEC §6, eq. 4.9)
};

struct SceneDef {
  std::string name = "scene";
  MaterialDef material;
  ContactDef contact;
  IntegrationDef integration;
  std::vector<SpeciesDef> species;
  std::optional<AvalancheDef> avalanche;  // the thesis scene; else explicit walls/particles
  PreparationDef preparation;
  RestDef rest;
  OutputDef output;
  std::vector<WallDef> walls;
  std::vector<ParticleDef> particles;
};

}  // namespace runout

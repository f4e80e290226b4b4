// From a scene definition to a ready World: derived parameters (SPEC §3), the thesis geometry
// and disc counts (SPEC §5, table 3.1), random pile placement, radius growth and settling.
#pragma once

#include <functional>
#include <vector>

#include "runout/measure.hpp"
#include "runout/scene.hpp"
#include "runout/checkpoint.hpp"
#include "runout/world.hpp"

namespace runout {

struct SceneSetup {
  ContactTable table;
  double tau_min = 0;        // s
  double dt = 0;             // s
  double unit_length = 0;    // d, m
  double unit_time = 0;      // sqrt(d/g), s
  double large_diameter = 0; // D, m
  SpeciesRoles roles;         // small and large among the species present
  int largest_species = 0;   // by nominal diameter, present or not
  std::vector<WallDef> walls;  // the scene's walls, thesis walls included
  int gate_wall = -1;          // index in walls of gate "A", or -1
  std::vector<int> counts;     // discs per species
};

// Every derived quantity of a scene. Throws ConfigError (naming `source`) for scenes that
// cannot be built, e.g. two explicit discs with the same centre.
SceneSetup derive_setup(const SceneDef& scene, const std::string& source = "scene");
// A scene that can be run: it has discs. Throws ConfigError naming `source`.
void check_runnable(const SceneDef& scene, const SceneSetup& setup, const std::string& source);

StepSettings step_settings(const SceneDef& scene, const SceneSetup& setup, int threads);

// SPEC eq. 3.1: n_s = %A_s N0 (D/d_s)^2, rounded up (table 3.1); for a class of a size
// distribution, d_s^-2 is its mean over the class's area (size_distribution.hpp).
double disc_count(const SpeciesDef& species, int reference_large_count, double large_diameter);

// A world holding the scene's explicit particles and walls.
World build_explicit_world(const SceneDef& scene, const SceneSetup& setup, int threads);
// The World a checkpoint of this scene holds (a cached pile, a run to resume), made once.
World restore_world(Checkpoint checkpoint, const SceneDef& scene, const SceneSetup& setup, int threads,
                    const std::string& name);

// The thesis pile (SPEC §5, fig. 3.1): centres at random in the box behind the gate, radii near
// zero and random velocities; then radii grow exponentially to their final values and the pile
// settles until its kinetic energy has gone, damped (preparation.damping) and then proved at
// rest without damping. `progress` is called every t* unit with (t*, E_k/E_p). Throws
// NumericalError if it does not settle within settle_max_time.
// What the preparation measured: when growth ended, when the pile was released, and E_k/E_p
// under the undamped law settle_hold t* after the damping was switched off (the proof that
// the pile is at rest under the flow's own law).
struct SettleReport {
  double t_star_grown = 0, t_star_settled = 0;
  double ek_over_ep_undamped = 0;
  int damped_rounds = 0;  // times the undamped hold failed and damping resumed
  double peak_impact_overlap = 0;  // World::peak_impact_overlap while the pile was prepared
};

World build_settled_pile(const SceneDef& scene, const SceneSetup& setup, int threads,
                         const std::function<void(double, double)>& progress = {},
                         SettleReport* report = nullptr);

// Removes gate "A" and sets the clock to t* = 0 (SPEC §5 release).
void release(World& world, const SceneSetup& setup);

}  // namespace runout

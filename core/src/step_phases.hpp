// The phases of a step as free functions over the World's SoA views (internal to core/src).
// World::step (world.cpp) calls them in order; each lives in its own file.
#pragma once

#include <vector>

#include "runout/world.hpp"

namespace runout::phases {

// What a phase reads of the world, built once per call (Box2D's b2StepContext habit).
struct StepContext {
  const StepSettings& settings;
  const ContactTable& table;
  const std::vector<Segment>& segments;
};

// Contact forces of every listed pair and disc–wall contact (contact_forces.cpp): writes the
// per-contact forces and torques and updates the history. `ledger_blocks` is scratch.
PassSums contact_forces(const StepContext& step, const Particles& p, PairContacts& pairs,
                        WallContacts& walls, std::vector<PassSums>& ledger_blocks,
                        StepProfile& profile);

// Spring energies and committed losses of the touching contacts now (contact_forces.cpp).
struct ContactEnergy {
  double elastic = 0, committed_normal = 0;
};
ContactEnergy contact_energy(const StepContext& step, const Particles& p,
                             const PairContacts& pairs, const WallContacts& walls);

// Sums each disc's contact forces and torques plus gravity into accelerations (eqs.
// 2.10–2.11), kicks v += a kick and drifts x += v drift (integrate.cpp). Returns the largest
// squared displacement since (x0, y0) and whether the state stayed finite.
struct Motion {
  double max_displacement2 = 0;
  bool finite = true;
};
Motion advance(const StepContext& step, Particles& p, const PairContacts& pairs,
               const WallContacts& walls, const std::vector<double>& x0,
               const std::vector<double>& y0, bool gather, double kick, double drift);

}  // namespace runout::phases

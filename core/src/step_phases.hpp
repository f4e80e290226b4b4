// The phases of a step as free functions over the World's SoA views (internal to core/src).
// World::step (world.cpp) calls them in order; each lives in its own file.
#pragma once

#include <cmath>
#include <limits>
#include <vector>

#include "runout/timing.hpp"
#include "runout/world.hpp"

namespace runout::phases {

// What a phase reads of the world, built once per call (Box2D's b2StepContext habit).
struct StepContext {
  const StepSettings& settings;
  const std::vector<Segment>& segments;
  // The contact model's parameter tables for pairs and for walls (ContactModel::Tables of
  // settings.contact's model, derive_laws), derived once with the World: derived at every
  // pass of every thread, they cost six allocations each time, ~0.5 us a pass and thread
  // (docs/performance_log.md, issue 11, thirty-fifth session).
  const LawTables& laws;
};
LawTables derive_laws(const ContactChoice& contact, const ContactTable& table);

// The contacts a thread computes for its block of discs [disc_lo, disc_hi): the pairs of the
// block's rows and its discs' wall contacts, each end moved up to the grain's next end.
using runout::ContactRange;
ContactRange contact_range(const PairContacts& pairs, const WallContacts& walls,
                           std::int64_t disc_lo, std::int64_t disc_hi, std::int64_t n,
                           ContactGrain grain);

// Where a force pass reads the contacts' history and where it writes their new history: two
// buffers taking turns, so a pass computed before the verdict on the step before it can be
// dropped (World::forces_and_motion), or one buffer where none is. Each is laid out as
// PairContacts::history.
struct HistoryTurn {
  const double* pairs_in;
  double* pairs_out;
  const double* walls_in;
  double* walls_out;
};

// Contact forces of the range's pairs and disc–wall contacts (contact_forces.cpp): writes the
// per-contact forces and torques and the new history. Returns the largest guarded overlap;
// with the ledger, the losses go to `ledger`'s blocks (LedgerBlocks::carry).
PassSums contact_forces(const StepContext& step, const Particles& p, PairContacts& pairs,
                        WallContacts& walls, const ContactRange& range, LedgerBlocks& ledger,
                        const HistoryTurn& history);

// Spring energies and committed losses of the touching contacts now (contact_forces.cpp).
struct ContactEnergy {
  double elastic = 0, committed_normal = 0;
};
ContactEnergy contact_energy(const StepContext& step, const Particles& p,
                             const PairContacts& pairs, const WallContacts& walls);

// Sums the contact forces and torques of each disc of [lo, hi) plus gravity into
// accelerations (eqs. 2.10–2.11) when `gather`, kicks v += a kick and drifts x += v drift
// (integrate.cpp). Returns how far the discs have moved since the lists were built at
// (x0, y0) and whether the state stayed finite. `lo` starts a window of lanes (DiscRuns).
struct Motion {
  // The box holding every disc's displacement since the rebuild, and the largest one.
  double ux_lo = std::numeric_limits<double>::infinity(), ux_hi = -ux_lo;
  double uy_lo = ux_lo, uy_hi = -ux_lo;
  double max_displacement2 = 0;
  bool finite = true;

  static Motion merge(const Motion& a, const Motion& b);
  // The box's diagonal: it bounds |u_i - u_j| for every pair (infinite once not finite).
  double spread() const;
  // The largest displacement: how much closer a disc came to a fixed wall.
  double largest() const { return std::sqrt(max_displacement2); }
};
// Where a pass puts the accelerations of discs [lo, hi): disc k's at [k - first].
struct Accelerations {
  double* x;
  double* y;
  double* angular;
  std::int64_t first = 0;
};
Motion advance(const StepContext& step, Particles& p, const PairContacts& pairs,
               const WallContacts& walls, const DiscRuns& runs, const HotArray<double>& x0,
               const HotArray<double>& y0, std::int64_t lo, std::int64_t hi, bool gather,
               double kick, double drift, const Accelerations& a);

}  // namespace runout::phases

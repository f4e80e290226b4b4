// The simulated system and its time step: discs, walls, the contact table and the neighbour
// lists. A step is a short list of named phases (SPEC §2, eqs. 2.15–2.18):
//   symplectic Euler:  [rebuild?] -> pair forces -> wall forces -> gather + kick + drift
//   velocity Verlet:   half kick + drift -> [rebuild?] -> pair forces -> wall forces -> gather + half kick
// One contact kernel serves pairs and walls (contact_forces.cpp) and takes the contact model
// (contact/registry.hpp) as a template argument. Every per-disc sum runs over a fixed list
// order, so results are bit-identical for any thread count (docs/performance.md).
// The phases live in one file each: world.cpp (the step, lists, reordering), contact_forces.cpp,
// integrate.cpp (force sums, kick and drift), energy.cpp, safety.cpp (SPEC §8 checks).
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

#include "runout/contact/registry.hpp"
#include "runout/derive.hpp"
#include "runout/handoff.hpp"
#include "runout/list_drift.hpp"
#include "runout/load_balance.hpp"
#include "runout/neighbor_list.hpp"
#include "runout/particles.hpp"
#include "runout/scene.hpp"
#include "runout/walls.hpp"

namespace runout {

// Constants of the step, built once (Box2D's b2StepContext habit).
struct StepSettings {
  double dt = 0;                     // s
  Eigen::Vector2d gravity{0, -9.81};  // m/s^2
  double skin = 0;                   // m
  IntegratorKind integrator = IntegratorKind::symplectic_euler;
  ContactChoice contact;  // the contact laws (frictional is set from the table)
  int threads = 1;
  double unit_time = 1;  // seconds per t*, for messages
  // Renumber discs spatially every this many steps (0: never); see World::reorder_discs.
  std::int64_t reorder_every = 0;
  // The run stops (NumericalError) when an impact (a contact loading faster than impact_rate)
  // overlaps beyond this share of the depth at which the contact would be passed through: for
  // a pair the sum of the radii (the centres meet), for a one-sided wall r + behind_depth(r)
  // (walls.hpp), for a two-sided plate r. The contact is far softer than the impact needs.
  // Measured against the pass-through depth rather than the smaller radius: a small disc
  // pinched by a heavy large one (D/d = 8.33) overlaps by its own radius with its centre still
  // far from the large disc's, which the thesis's stiffness design allows.
  double overlap_guard = 0.75;
  double impact_rate = 0;  // m/s: only contacts loading faster than this are guarded
  bool track_energy = false;  // keep the dissipation ledger (costs a little in the pair pass)
  // Local non-viscous damping (PFC's): each acceleration component loses this share of its
  // magnitude against the motion. Only while a pile settles (setup.cpp); 0 in every flow.
  double local_damping = 0;
  // When a step of several threads starts its forces before the verdict on the step before
  // (World::forces_and_motion): where the lists' bound leaves room for it, always (tests: every
  // region a verdict ends then drops a step's forces), or never. No result depends on it.
  enum class Ahead { when_safe, always, never };
  Ahead ahead = Ahead::when_safe;
};

// Wall-clock seconds spent in each phase since construction.
struct StepProfile {
  double contact_forces = 0, integrate = 0, rebuild = 0;  // contact forces: pairs and walls
  std::int64_t rebuilds = 0;
  // Steps of several threads whose forces started before the verdict on the step before,
  // and those of them dropped because that verdict ended the parallel region.
  std::int64_t steps_ahead = 0, steps_dropped = 0;
};

// What one force pass returns besides the forces: the largest guarded overlap share and, with
// the ledger, the energy it dissipated (J).
struct PassSums {
  double worst = 0, loss_normal = 0, loss_friction = 0, loss_rolling = 0;
  // Two passes' sums together: the larger overlap share, the losses added (a's first).
  friend PassSums operator+(const PassSums& a, const PassSums& b) {
    return {std::max(a.worst, b.worst), a.loss_normal + b.loss_normal,
            a.loss_friction + b.loss_friction, a.loss_rolling + b.loss_rolling};
  }
};

// The force pass's ledger sums per fixed block of contacts (kPairLedgerBlock,
// kWallLedgerBlock), added in block order whatever thread computed each block
// (contact_forces.cpp): scratch of the World.
struct LedgerBlocks {
  // A cache line each: two threads write the blocks on either side of their boundary.
  struct alignas(64) Block {
    PassSums sums;
  };
  // The pass's sums so far, pairs' and walls' apart: each is added from zero in block order,
  // the pairs' and the walls' sums then added (total). A thread carries on its predecessor's
  // partial over its own blocks, so the pass's total has the same bits as one thread's while
  // no thread reads the other's blocks (docs/performance_log.md, issue 11 forty-sixth session).
  struct Partial {
    PassSums pairs, walls;
    PassSums total() const { return pairs + walls; }
  };
  std::vector<Block> pairs, walls;
  void size_for(const PairContacts& pairs, const WallContacts& walls);
  // `from` carried on over the blocks of `range`, whose ends are ends of blocks.
  Partial carry(Partial from, const ContactRange& range) const;
};

// Energy lost since the World was made (J): normal (Walton–Braun hysteresis of contacts that
// ended, or dashpot work), Coulomb sliding, and rolling resistance. Kept only with
// StepSettings::track_energy.
struct Dissipation {
  double normal = 0, friction = 0, rolling = 0;
};

// The energy ledger at one instant (SPEC §8): kinetic, potential above `reference_y`, elastic
// (normal, tangential and rolling springs), and the loss committed by live Walton–Braun contacts.
struct EnergyState {
  double translational = 0, rotational = 0, potential = 0;
  double elastic = 0, committed_normal = 0;
};

inline constexpr int kMaxThreads = 256;

namespace phases { struct Motion; }  // step_phases.hpp

// The contact model's parameter tables (ContactModel::Tables) for pairs and for walls, held
// without their type: derived once from the World's table (phases::derive_laws).
struct LawTables {
  std::shared_ptr<const void> pairs, walls;
};

class World {
 public:
  World(Particles particles, std::vector<Segment> segments, ContactTable table,
        StepSettings settings);

  void step() { advance(1); }
  // `steps` steps, as many of them as can be in one parallel region together: a region ends
  // only where the lists must be rebuilt or the blocks move (every LoadBalance::kPeriod
  // steps), so the team is not started and joined at every step (docs/performance_log.md,
  // issue 11, twenty-first session). The same bits as `steps` calls of step().
  void advance(std::int64_t steps);

  const Particles& particles() const { return particles_; }
  const std::vector<Segment>& segments() const { return segments_; }
  const ContactTable& table() const { return table_; }
  const StepSettings& settings() const { return settings_; }
  const PairContacts& pairs() const { return pairs_; }
  const WallContacts& wall_contacts() const { return wall_contacts_; }
  const StepProfile& profile() const { return profile_; }
  const Dissipation& dissipation() const { return ledger_; }
  // The largest impact overlap the guard has seen, as a share of the pass-through depth.
  double peak_impact_overlap() const { return peak_impact_overlap_; }
  // False when mu = 0 for every contact: no tangential history is kept or computed.
  bool frictional() const { return settings_.contact.frictional; }
  // Doubles of history per contact the contact model keeps (contact.hpp).
  int history_width() const { return history_width_; }
  void set_track_energy(bool on) { settings_.track_energy = on; }
  void set_dissipation(const Dissipation& d) { ledger_ = d; }
  EnergyState energy(double reference_y) const;
  // Largest overlap / smaller radius (a wall: the disc's radius) among touching contacts now.
  double largest_overlap_share() const;
  double time() const { return time_; }            // s since the clock was last set
  std::int64_t step_count() const { return steps_; }

  void set_threads(int threads) { settings_.threads = std::clamp(threads, 1, kMaxThreads); }
  void set_ahead(StepSettings::Ahead ahead) { settings_.ahead = ahead; }
  void set_clock(double time, std::int64_t steps) { time_ = time; steps_ = steps; }
  // `radius_scale`: the share of their final radii every disc has now (radius growth), so the
  // guard judges overlaps against the final radii.
  void set_overlap_guard(double share, double radius_scale = 1.0) {
    settings_.overlap_guard = share;
    guard_radius_scale_ = radius_scale;
  }
  void set_local_damping(double share) { settings_.local_damping = share; }
  // Puts every contact back on its loading line (forgets the largest overlaps reached): the
  // dents left by radius growth during preparation are not material history.
  void forget_normal_history();
  // Stops a wall from acting (the gate at release, SPEC §5). Its contacts end now.
  void deactivate_wall(int wall_index);
  void deactivate_wall_segment(std::size_t segment);
  // Changes one disc's size (radius growth during preparation).
  void resize_disc(std::size_t k, double radius, double mass, double inertia);
  // Restores contact history read from a checkpoint (lists are rebuilt, keys matched).
  void restore_history(const PairContacts& pairs, const WallContacts& walls);

 private:
  void rebuild_lists();
  void reorder_discs();
  // With `forces`: contact forces, then a from the contact sums; then kick v += a kick and
  // drift x += v drift. One parallel region: each thread takes its block of discs (blocks_)
  // and hands the rows that reach the next block to its thread (Handoff). Up to `passes`
  // such passes in the region, while the lists hold and the blocks stay; returns how many.
  std::int64_t forces_and_motion(bool forces, double kick, double drift, std::int64_t passes);
  // What a pass means for the next one; every thread of a region works out the same.
  struct Verdict {
    double list_drift = 0;  // list_drift_ after the pass (see below)
    bool spent = false;     // the whole flow's bound is spent: the groups' bound counts
    bool closing = false;   // ... and must first be measured over all discs (ListDrift::closing)
    bool go_on = false;     // the lists hold, the state is finite, no guard tripped
  };
  // `watched`: the blocks measured their groups into `slot`, with their terms in `blocks`.
  Verdict judge(const PassSums& sums, const phases::Motion& motion, bool watched,
                const ListDrift::Partial& blocks, int slot) const;
  void check_finite() const;
  // The last two verdicts (recent_[1] the last), and how many were given since the rebuild.
  Verdict recent_[2];
  std::int64_t recent_count_ = 0;
 public:
  // Throws NumericalError if a disc has left the walls' bounding box by more than `margin`
  // (it passed through a wall and would fall for ever). No walls: no check.
  void check_escape(double margin) const;
 private:
  void check_overlap(double worst);
  // Whether a pass's largest guarded overlap share (or a NaN) is beyond the guard.
  bool beyond_guard(double worst) const { return !(worst * guard_radius_scale_ <= settings_.overlap_guard); }

  Particles particles_;
  std::vector<Segment> segments_;
  ContactTable table_;
  StepSettings settings_;
  int history_width_ = 0, normal_history_width_ = 0;  // doubles per contact (contact.hpp)
  NeighborSearch search_;
  PairContacts pairs_;
  WallContacts wall_contacts_;
  DiscRuns runs_;  // each disc's contacts in summing order (neighbor_list.hpp)
  StepProfile profile_;
  Dissipation ledger_;
  double time_ = 0;
  std::int64_t steps_ = 0;

  LawTables laws_;  // the contact model's parameter tables, derived with the World

  // Each thread's accelerations of its block's discs in a pass of several threads
  // (phases::Accelerations), each on pages of its own: written into the discs' arrays, a
  // thread's stream ran on into the next block's lines (docs/performance_log.md, issue 11,
  // thirty-fifth session). Velocity Verlet keeps its accelerations in Particles between calls.
  struct BlockAccelerations {
    HotArray<double> x, y, angular;  // of discs first, first + 1, ... of the block
    std::int64_t first = 0;
  };
  std::vector<BlockAccelerations> block_accelerations_;

  // Verlet-list validity (SPEC §5): see World::step.
  HotArray<double> x_at_rebuild_, y_at_rebuild_, radius_at_rebuild_;
  double list_drift_ = 0;  // bound on how much closer any two bodies came since the rebuild (m)
  ListDrift drift_;         // judges list_drift_ group by group
  bool watch_groups_ = false;  // the last step needed the groups' bound (ListDrift)
  double max_growth_ = 0;
  bool lists_valid_ = false;
  double guard_radius_scale_ = 1.0;
  double peak_impact_overlap_ = 0;  // largest guarded share seen (see overlap_guard)
  bool finite_ = true;
  // By pass, in turn (ListDrift::kSlots): a pass's sums are read while later ones are written.
  LedgerBlocks ledger_blocks_[ListDrift::kSlots];
  // The history's other buffer (phases::HistoryTurn): a force pass writes here, and the two
  // are swapped once it counts.
  HotArray<double> pair_history_next_, wall_history_next_;
  // Each thread's block of discs for a whole step (load_balance.hpp) and what hands one
  // block's results to the next (World::forces_and_motion).
  LoadBalance blocks_{LoadBalance::Work::step};
  Handoff handoff_;
  std::int64_t lists_version_ = 0;  // counts rebuilds of the lists
  // Per thread: the last pass whose boundary pairs it has computed. Copies start fresh, and
  // so does a world assigned over: its pass count is the assigned one's, and a flag left at a
  // pass it reaches later would let a thread skip its wait.
  struct ReadyFlags {
    // `pass`: the boundary pairs are done; `moved`: the discs earlier blocks reach have moved
    // (their pushes read, their new state out); `done`: the whole pass is (its outcome is out);
    // `carried`: the ledger's partial is carried over the block's contacts.
    struct alignas(64) Flag { std::atomic<std::int64_t> pass{-1}, moved{-1}, done{-1}, carried{-1}; };
    std::unique_ptr<Flag[]> flag = std::make_unique<Flag[]>(kMaxThreads);
    ReadyFlags() = default;
    ReadyFlags(const ReadyFlags&) : ReadyFlags() {}
    ReadyFlags& operator=(const ReadyFlags&) {
      for (int t = 0; t < kMaxThreads; ++t) {
        flag[t].pass.store(-1, std::memory_order_relaxed);
        flag[t].moved.store(-1, std::memory_order_relaxed);
        flag[t].done.store(-1, std::memory_order_relaxed);
        flag[t].carried.store(-1, std::memory_order_relaxed);
      }
      return *this;
    }
  } ready_;
  std::int64_t passes_ = 0;  // force-and-motion passes taken (the flags' values)
};

}  // namespace runout

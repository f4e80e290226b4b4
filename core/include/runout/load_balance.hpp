// Which discs each thread takes in a step (World::forces_and_motion). No result
// depends on it: each contact's force and each disc's sum are the same bits whoever computes
// them (world.hpp), so the blocks follow the threads' measured speed. On a shared machine one
// core can run a third slower than the other for seconds at a time (docs/performance_log.md), and
// blocks of equal estimated work would leave the faster thread waiting at every step.
#pragma once

#include <cstdint>
#include <vector>

#include "runout/neighbor_list.hpp"

namespace runout {

class LoadBalance {
 public:
  // What a block's work is counted in: the contacts of its rows (the force pass), its run
  // slots and lanes (the sums, kick and drift), or both (a whole step: a contact costs about
  // six slots on the thesis pile, docs/performance_log.md).
  enum class Work { contacts, sums, step };
  // Steps between two moves of the blocks' ends.
  static constexpr int kPeriod = 16;

  explicit LoadBalance(Work work) : work_(work) {}

  // Blocks of equal estimated work when the disc count or the thread count has changed;
  // otherwise the blocks stay as they are.
  void prepare(const PairContacts& pairs, const WallContacts& walls, const DiscRuns& runs,
               std::int64_t n, int threads);
  // Thread t's block of discs is [bounds()[t], bounds()[t + 1]); each end but the last starts
  // a window of lanes (DiscRuns::kWindow).
  const std::vector<std::int64_t>& bounds() const { return bounds_; }
  // Thread t was busy (not waiting) for `seconds` in this step's phase.
  void record(int t, double seconds) { busy_[static_cast<std::size_t>(t)].seconds += seconds; }
  // Every kPeriod steps, moves the blocks' ends so each thread's share of the estimated work
  // follows its measured speed (work done per busy second, smoothed over a few periods);
  // ends that would each move by one window at most stay (jitter, load_balance.cpp).
  void after_step(const PairContacts& pairs, const WallContacts& walls, const DiscRuns& runs);
  // Steps from now to the one whose after_step may move the ends (that step included): a
  // parallel region of several steps ends there (World::forces_and_motion).
  int steps_before_turn() const { return kPeriod - steps_; }
  // Changes whenever the blocks move.
  std::int64_t version() const { return version_; }

 private:
  void estimate(const PairContacts& pairs, const WallContacts& walls, const DiscRuns& runs);
  void place();

  Work work_;
  std::int64_t n_ = -1;
  int threads_ = 0, steps_ = 0;
  std::int64_t version_ = 0;
  std::vector<std::int64_t> bounds_;
  // Each thread's busy time on a cache line of its own: the threads add to theirs every step.
  struct alignas(64) Busy {
    double seconds = 0;
  };
  std::vector<Busy> busy_;
  std::vector<double> speed_;
  std::vector<std::int64_t> work_before_;  // estimated work before each window
};

}  // namespace runout

// How a step of several threads hands one block's results to the next (World::forces_and_motion).
// Thread t takes the discs of block t: the contacts of their rows, then their sums, kick and
// drift. A pair's rows belong to its lower index i, so the pairs of the last rows of block t
// reach discs j of later blocks (the crossing pairs): their pushes on j are summed by the
// later thread. Thread t computes those rows first and raises its flag; a later thread sums
// the discs they reach only after that flag.
// The crossing pushes on j are copied into a packed area at the end of PairContacts' pushes,
// and those discs' runs read them there: a later thread then pulls a few cache lines written
// for it alone from the other core, rather than every line of the pushes array holding one
// (118 crossing pairs on the bench pile: 118 doubles, ~15 lines an array, where the pushes in
// place were spread over 37 measured lines). The copies hold
// the same bits and each run keeps its order, so no sum changes (docs/performance_log.md, issue 11
// sixteenth session).
#pragma once

#include <cstdint>
#include <vector>

#include "runout/neighbor_list.hpp"

namespace runout {

// The ledger sums its losses per fixed block of contacts (LedgerBlocks, world.hpp), each
// computed by one thread in one piece, so a thread's contacts end at a block end. A block is
// then also how far a thread's contacts reach into the next thread's discs, whose state
// crosses between the cores every step: small blocks keep that short (64 pairs rather than
// 256 took ~1.2 us off a two-thread step; docs/performance_log.md, fifteenth session).
inline constexpr std::int64_t kPairLedgerBlock = 64;
inline constexpr std::int64_t kWallLedgerBlock = 16;
// Where a thread's contacts may end. Without the ledger nothing is summed in blocks: a
// thread's pairs end at a cache line of pushes (8) and its wall contacts exactly at its
// block's last disc. A wall block of 16 held the floor discs of ~15 later columns, so the
// later thread's first ~370 discs waited for the earlier thread's flag, not ~170 (the bench
// pile; docs/performance_log.md, twenty-second session).
struct ContactGrain {
  std::int64_t pairs = kPairLedgerBlock, walls = kWallLedgerBlock;
  bool operator==(const ContactGrain&) const = default;
};
inline ContactGrain contact_grain(bool ledger) {
  return ledger ? ContactGrain{} : ContactGrain{8, 1};
}

// Pairs [pair_lo, pair_hi) and wall contacts [wall_lo, wall_hi): what one thread computes.
struct ContactRange {
  std::int64_t pair_lo = 0, pair_hi = 0, wall_lo = 0, wall_hi = 0;
};

class Handoff {
 public:
  // Whether find() was called for these lists, blocks, grain and thread count.
  bool current(std::int64_t lists_version, std::int64_t blocks_version, ContactGrain grain,
               int threads) const {
    return lists_ == lists_version && blocks_ == blocks_version && grain_ == grain &&
           range.size() == static_cast<std::size_t>(threads);
  }
  // Each thread's contacts for the blocks `bounds` (bounds[t], bounds[t + 1]) of the current
  // lists, its first boundary pair, the first disc of each block no earlier thread reaches,
  // and the crossing pairs, whose pushes on j move to the packed area (pairs' pushes grown,
  // runs pointed there). The runs must be those of `lists_version`.
  void find(PairContacts& pairs, const WallContacts& walls, DiscRuns& runs,
            const std::vector<std::int64_t>& bounds, std::int64_t lists_version,
            std::int64_t blocks_version, ContactGrain grain);
  // Copies thread t's crossing pushes into the packed area; after its boundary pairs and
  // before its flag.
  void publish(int t, PairContacts& pairs) const;
  // Fetches thread t's packed pushes into this core's cache ahead of the sums that read them.
  void prefetch(int t, const PairContacts& pairs) const;
  // Points every run back at the pushes in place (a pass of one thread reads no packed area).
  void release(const PairContacts& pairs, DiscRuns& runs, std::int64_t lists_version);

  std::vector<ContactRange> range;  // thread t's contacts
  // Thread t computes its pairs from boundary_pair[t] on first: the rows that touch a later
  // block's discs. Its discs below first_free[t] wait for the earlier threads' such rows.
  std::vector<std::int64_t> boundary_pair, first_free;

 private:
  std::int64_t lists_ = -1, blocks_ = -1;  // the versions found for
  ContactGrain grain_;
  // The crossing pairs, thread by thread: thread t's are crossing_[crossing_start_[t] ..
  // crossing_start_[t + 1]), the i-th of them packed at pushes index 2 size() + 1 + i.
  std::vector<std::int32_t> crossing_;
  std::vector<std::int64_t> crossing_start_;
  // The runs of lists_ point at the packed area while lists_ is current and crossing_ is not
  // empty; release() undoes that and forgets lists_.
};

}  // namespace runout

// Contact search (SPEC §5): a cell grid finds, at each rebuild, every disc pair and disc–wall
// pair closer than the skin; between rebuilds only these listed pairs are tested. Contact
// history lives beside the pairs and is carried across rebuilds by matching (i, j) keys
// (SPEC §2: it must survive neighbour-list rebuilds).
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "runout/cell_grid.hpp"
#include "runout/particles.hpp"
#include "runout/walls.hpp"

namespace runout {

// Disc–disc candidate pairs, i < j, sorted by (i, j).
struct PairContacts {
  HotArray<std::int32_t> i, j;
  // History (SPEC §2): history_width columns, contact q's value m at history[m * size() + q],
  // laid out by the contact model (contact.hpp: normal | tangential | rolling), e.g.
  // overlap_max and the tangential spring.
  HotArray<double> history;
  int history_width = 0;
  // This step's push of pair q on i at [q], and on j at [j_offset() + q] (the force opposite,
  // the torque the law gives j), so each disc's sum reads one array (DiscRuns); [zero_push()]
  // is always zero. In a pass of several threads a packed copy of the pushes that cross to a
  // later thread's discs starts at [packed_area()] (Handoff). Each of these parts starts a
  // cache line and a free line precedes it: the threads write the two ends of the pushes on i
  // and on j, and no line may be written by two of them (hot_array.hpp).
  HotArray<double> fx, fy, torque;
  HotArray<std::int32_t> row_start;  // pairs whose i == k: [row_start[k], row_start[k+1])
  // Row of the contact parameter table (species_i * species_count + species_j), set with the
  // lists by the World (the search does not know the table).
  HotArray<std::int32_t> kind;

  std::size_t size() const { return i.size(); }
  std::size_t j_offset() const { return after_a_free_line(size()); }
  std::size_t zero_push() const { return after_a_free_line(j_offset() + size()); }
  std::size_t packed_area() const { return after_a_free_line(zero_push() + 1); }

  // The first start of a cache line of doubles at or after `end` + one line.
  static constexpr std::size_t after_a_free_line(std::size_t end) {
    constexpr std::size_t kLine = 64 / sizeof(double);
    return (end + 2 * kLine - 1) / kLine * kLine;
  }
};

// Disc–wall-segment candidate pairs, sorted by (disc, segment).
struct WallContacts {
  HotArray<std::int32_t> disc, segment;
  HotArray<double> history;  // as PairContacts
  int history_width = 0;
  HotArray<double> fx, fy, torque;  // force and torque on the disc
  HotArray<std::int32_t> row_start;  // per disc

  std::size_t size() const { return disc.size(); }
};

// Each disc's pairs in the order its force sum takes (eqs. 2.10–2.11): its own row (it is i,
// by j), then the pairs where it is j (by i); its walls (WallContacts rows) come after. The
// order is a function of the lists alone, and pairs that do not touch push exactly zero, so
// sums are bit-identical for any thread count and skin.
// The runs are laid out kSlice discs side by side (a sliced ELLPACK layout): slice g holds
// the discs lane_disc[kSlice g + l], slot s of lane l at slice_start[g] + kSlice s + l, each
// lane padded to the slice's longest run with the push that is always zero (a sum started at
// +0 is never -0, so adding +0 changes no bit). A slice's sums are then one loop over its
// slots for all its lanes at once: no exit per disc to predict. The lanes of each window of
// kWindow discs hold that window's discs longest run first, so a large disc shares its slice
// with large ones rather than padding three small ones to its length (D/d = 4: 1.43 slots per
// push with consecutive discs). Rebuilt with the lists.
struct DiscRuns {
  static constexpr std::int32_t kSlice = 4;
  static constexpr std::int32_t kWindow = 32;  // discs; a multiple of kSlice
  HotArray<std::int32_t> slice_start;  // slice g: slots [slice_start[g], slice_start[g + 1])
  HotArray<std::int32_t> source;       // slot -> index into PairContacts::fx, fy, torque
  HotArray<std::int32_t> lane_disc;    // kSlice g + l -> disc of that lane, -1 past the last
  HotArray<std::int32_t> incoming;     // pair q -> the slot of its push on j (Handoff)

  std::size_t slices() const { return slice_start.empty() ? 0 : slice_start.size() - 1; }
};

// Thread t of T's discs [first, second) where a rebuild or its follow-up writes per thread:
// block t of the step (`blocks`, LoadBalance::bounds) where the blocks fit the team, so each
// thread writes what its step reads; else an equal share. Either way the blocks run in thread
// order over [0, n), so the lists are the same for any thread count.
inline std::pair<std::int64_t, std::int64_t> team_block(const std::vector<std::int64_t>& blocks,
                                                        std::int64_t n, int t, int T) {
  if (static_cast<int>(blocks.size()) == T + 1 && blocks.back() == n) return {blocks[t], blocks[t + 1]};
  return {n * t / T, n * (t + 1) / T};
}

class NeighborSearch {
 public:
  // Rebuilds both lists for the current positions, keeping the history of pairs present before
  // and after. `reach` is the skin: pairs with gap < skin are listed. Each contact keeps
  // `history_width` doubles of history (the contact model's). With `threads` threads; where
  // `blocks` are a block of discs for each of them (LoadBalance::bounds), each thread builds
  // the rows of its block, else of an equal share.
  void rebuild(const Particles& p, const std::vector<Segment>& segments, double skin,
               int threads, const std::vector<std::int64_t>& blocks, int history_width,
               PairContacts& pairs, WallContacts& walls, DiscRuns& runs);
  // Per disc, from the last rebuild: how far it can move before it could touch an active wall
  // segment it is not listed with (at least the skin; infinite without walls). ListDrift.
  const std::vector<double>& wall_margin() const { return wall_margin_; }
  // The largest radius at the last rebuild (0 without discs).
  double largest_radius() const { return largest_radius_; }

 private:
  void runs_of(const PairContacts& pairs, DiscRuns& runs, int t, int T, std::int32_t lo,
               std::int32_t hi);

  std::vector<double> wall_margin_;
  double largest_radius_ = 0;
  CellGrid grid_;
  // What each thread of the rebuild's team sums of its block, for the others (own lines).
  struct alignas(64) TeamSlot {
    double fine_radius = 0;
    std::int32_t walls = 0, pairs = 0;
  };
  std::vector<TeamSlot> team_;
  std::vector<std::vector<std::int32_t>> thread_j_;     // per thread, pairs of its rows
  std::vector<std::vector<std::pair<std::int32_t, std::int32_t>>> thread_foreign_;  // of others' rows
  std::vector<std::vector<std::int32_t>> chunk_walls_;  // per chunk of discs, then merged
  std::vector<std::vector<std::int32_t>> thread_count_;  // per thread: its rows' pairs, then cursors
  std::vector<std::int32_t> lane_of_;  // disc -> its lane (DiscRuns::lane_disc)
  std::vector<std::int32_t> run_length_;  // disc -> pairs in its run
  PairContacts old_pairs_;
  WallContacts old_walls_;
};

}  // namespace runout

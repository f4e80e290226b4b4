// When the neighbour lists go stale (SPEC §5), judged group by group once the whole flow's
// bound is spent. The lists hold every pair closer than the skin at the rebuild, so an unlisted
// pair touches only once its two discs have come closer by the skin (less their growth). The
// displacements since the rebuild bound that: for two discs of one group of kGroup consecutive
// discs, or of two groups close to each other, by the spread of those groups' displacements;
// for discs of groups farther apart (by `far_slack` beyond the skin), by the spread of all of
// them; for a disc and a wall it is not listed with, by the disc's displacement less how much
// farther than the skin the wall was (NeighborSearch::wall_margin). A flow that shears then
// does not stale its lists in one place because another place moves differently, nor because
// the flow slides along the bed; the discs are numbered along the flow
// (World::reorder_discs), so a group is a narrow slice of it.
#pragma once

#include <algorithm>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "runout/hot_array.hpp"

namespace runout {

class ListDrift {
 public:
  static constexpr std::size_t kGroup = 32;  // discs

  // Groups whose centres are farther apart than two of the largest discs and kFarSkins skins
  // reach each other only once the whole flow's spread has grown by kFarSkins - 1 skins.
  static constexpr double kFarSkins = 4;

  // At a rebuild, with the largest radius: groups whose centres are within 2 r_max + kFarSkins
  // skins are near each other. The groups are found when first needed.
  void rebuilt(double largest_radius, double skin);
  // A bound, to hold against the skin, on how much closer two unlisted bodies came since the
  // rebuild, from the centres now (x, y) and at the rebuild (x0, y0), each disc's wall margin
  // at the rebuild, and the spread of all displacements (the diagonal of their box).
  double closing(const HotArray<double>& x, const HotArray<double>& y,
                 const HotArray<double>& x0, const HotArray<double>& y0,
                 const std::vector<double>& wall_margin, double all_spread);
  // The same in parts, so threads measure their own discs side by side: once the groups are
  // found (since the last `closing`, no rebuild), `split` by the threads' blocks of discs
  // (whole groups); each block's `measure` then boxes its groups' displacements and takes
  // the bound's terms within the block (its groups and the near pairs inside it), and
  // `bound` adds the near pairs across blocks. The boxes are kept in three slots, by step in
  // turn, so a thread may measure a step's discs while the others still take an earlier
  // step's bound (World::forces_and_motion: a thread may be a step ahead of another, and
  // computes the next step's forces before the step's verdict).
  static constexpr int kSlots = 3;
  struct Partial {  // a block's terms: the largest squared spread, the largest wall closing
    double pairs2 = 0, walls = -std::numeric_limits<double>::infinity();
    static Partial merge(const Partial& a, const Partial& b) {
      return {std::max(a.pairs2, b.pairs2), std::max(a.walls, b.walls)};
    }
  };
  bool found() const { return found_; }
  void split(const std::vector<std::int64_t>& bounds);
  Partial measure(const HotArray<double>& x, const HotArray<double>& y,
                  const HotArray<double>& x0, const HotArray<double>& y0, int block, int slot);
  double bound(double all_spread, const Partial& blocks, int slot) const;

 private:
  void find_groups(const HotArray<double>& x0, const HotArray<double>& y0,
                   const std::vector<double>& wall_margin);
  // The largest squared spread of the near pairs by_block_[from, to) (their boxes in `slot`).
  double pairs2_of(std::size_t from, std::size_t to, int slot) const;

  double reach_ = 0, far_slack_ = 0, skin_ = 0;
  bool found_ = false;
  std::vector<double> box_[kSlots];              // 4 per group: centres, then displacements
  std::vector<double> wall_slack_;               // per group: its smallest wall margin less the skin
  std::vector<std::pair<std::int32_t, std::int32_t>> near_;  // pairs of groups near each other
  // By `split`: the blocks' ends, the near pairs inside each block (block t's from
  // inside_start_[t]) and then those across blocks (from inside_start_[blocks]).
  std::vector<std::int64_t> split_bounds_;
  std::vector<std::pair<std::int32_t, std::int32_t>> by_block_;
  std::vector<std::size_t> inside_start_;
  std::vector<std::int32_t> by_x_;
};

}  // namespace runout

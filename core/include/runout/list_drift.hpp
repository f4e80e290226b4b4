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
// (World::reorder_discs), so a group is compact.
#pragma once

#include <cstdint>
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
  // The same in two parts, so threads can measure their own discs side by side: once the
  // groups are found (since the last `closing`, no rebuild), each group's box of
  // displacements for the discs [lo, hi) (lo starts a group), then the bound from them all.
  bool found() const { return found_; }
  void measure(const HotArray<double>& x, const HotArray<double>& y,
               const HotArray<double>& x0, const HotArray<double>& y0, std::size_t lo,
               std::size_t hi);
  double bound(double all_spread) const;

 private:
  void find_groups(const HotArray<double>& x0, const HotArray<double>& y0,
                   const std::vector<double>& wall_margin);

  double reach_ = 0, far_slack_ = 0, skin_ = 0;
  bool found_ = false;
  std::vector<double> box_;                      // 4 per group: centres, then displacements
  std::vector<double> largest2_;                 // per group: its largest |u|^2
  std::vector<double> wall_slack_;               // per group: its smallest wall margin less the skin
  std::vector<std::pair<std::int32_t, std::int32_t>> near_;  // pairs of groups near each other
  std::vector<std::int32_t> by_x_;
};

}  // namespace runout

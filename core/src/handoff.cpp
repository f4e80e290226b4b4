// Which contacts each thread of a step computes and how the crossing pushes reach the later
// threads (handoff.hpp, World::forces_and_motion).
#include "runout/handoff.hpp"

#include <algorithm>

#include "step_phases.hpp"

namespace runout {

void Handoff::find(PairContacts& pairs, const WallContacts& walls, DiscRuns& runs,
                   const std::vector<std::int64_t>& b, std::int64_t lists_version,
                   std::int64_t blocks_version, ContactGrain grain) {
  release(pairs, runs, lists_version);
  const std::int64_t n = b.back();
  const int T = static_cast<int>(b.size()) - 1;
  range.resize(static_cast<std::size_t>(T));
  boundary_pair.assign(static_cast<std::size_t>(T), 0);
  first_free.assign(static_cast<std::size_t>(T), 0);
  crossing_.clear();
  crossing_start_.assign(static_cast<std::size_t>(T) + 1, 0);
  std::int64_t reached = 0;  // the end of the discs the threads before t reach
  for (int t = 0; t < T; ++t) {
    const ContactRange r = phases::contact_range(pairs, walls, b[t], b[t + 1], n, grain);
    range[t] = r;
    // Block t's discs below what earlier threads reach wait for them; windows of lanes whole.
    constexpr std::int64_t W = DiscRuns::kWindow;
    first_free[t] = std::min(b[t + 1], (std::max(b[t], reached) + W - 1) / W * W);
    std::int64_t first = r.pair_hi, reach = b[t + 1];
    // The last block's pairs reach no later disc (this serial scan reads lines the other
    // threads' rebuild wrote: ~10 us a find on the bench pile at two threads).
    const std::int64_t scan_end = t + 1 < T ? r.pair_hi : r.pair_lo;
    for (std::int64_t q = r.pair_lo; q < scan_end; ++q)
      if (pairs.j[q] >= b[t + 1]) {  // j > i: a pair whose i is beyond the block crosses too
        first = std::min(first, q);
        reach = std::max<std::int64_t>(reach, pairs.j[q] + 1);
        crossing_.push_back(static_cast<std::int32_t>(q));
      }
    // The walls of the range are all computed before the flag; their discs may be beyond the
    // block where the range's end was moved up to the grain's end.
    for (std::int64_t q = r.wall_lo; q < r.wall_hi; ++q)
      reach = std::max<std::int64_t>(reach, walls.disc[q] + 1);
    // At the grain, so the ledger's blocks are each computed in one piece.
    boundary_pair[t] = std::min(r.pair_hi, std::max(r.pair_lo, first / grain.pairs * grain.pairs));
    reached = std::max(reached, reach);
    crossing_start_[t + 1] = static_cast<std::int64_t>(crossing_.size());
  }
  // The packed area follows the push that is always zero; each crossing pair's slot in its
  // j's run reads its copy there.
  const std::size_t area = pairs.packed_area();
  pairs.fx.resize(area + crossing_.size());
  pairs.fy.resize(area + crossing_.size());
  pairs.torque.resize(area + crossing_.size());
  for (std::size_t c = 0; c < crossing_.size(); ++c)
    runs.source[runs.incoming[crossing_[c]]] = static_cast<std::int32_t>(area + c);
  lists_ = lists_version;
  blocks_ = blocks_version;
  grain_ = grain;
}

void Handoff::publish(int t, PairContacts& pairs) const {
  const auto area = static_cast<std::int64_t>(pairs.packed_area());
  const auto on_j = static_cast<std::int64_t>(pairs.j_offset());
  double* __restrict fx = pairs.fx.data();
  double* __restrict fy = pairs.fy.data();
  double* __restrict torque = pairs.torque.data();
  for (std::int64_t c = crossing_start_[t]; c < crossing_start_[t + 1]; ++c) {
    const std::int64_t from = on_j + crossing_[c];
    fx[area + c] = fx[from];
    fy[area + c] = fy[from];
    torque[area + c] = torque[from];
  }
}

void Handoff::prefetch(int t, const PairContacts& pairs) const {
  const auto area = static_cast<std::int64_t>(pairs.packed_area());
  for (std::int64_t c = crossing_start_[t]; c < crossing_start_[t + 1]; c += 8) {
    __builtin_prefetch(pairs.fx.data() + area + c);
    __builtin_prefetch(pairs.fy.data() + area + c);
    __builtin_prefetch(pairs.torque.data() + area + c);
  }
}

void Handoff::release(const PairContacts& pairs, DiscRuns& runs, std::int64_t lists_version) {
  // Runs of other lists were laid out afresh by their rebuild.
  if (lists_ != lists_version) return;
  const auto on_j = static_cast<std::int32_t>(pairs.j_offset());
  for (const std::int32_t q : crossing_) runs.source[runs.incoming[q]] = on_j + q;
  lists_ = -1;  // found again before the next pass of several threads
}

}  // namespace runout

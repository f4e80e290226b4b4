// The threads' blocks of discs (load_balance.hpp): they cover every disc once, start at
// windows of lanes, split the estimated work evenly at first and follow the measured speeds.
// That nothing computed depends on them is Determinism.* (test_neighbors.cpp) and the
// trajectory hash at 1 and 2 threads (test_trajectory.cpp).
#include <gtest/gtest.h>

#include <random>

#include "runout/load_balance.hpp"
#include "runout/walls.hpp"

namespace runout {
namespace {

struct Lists {
  PairContacts pairs;
  WallContacts walls;
  DiscRuns runs;
  std::int64_t n = 0;
};

// A bidisperse heap denser on the left, so equal disc counts are not equal work.
Lists heap(int n) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Particles p;
  for (int k = 0; k < n; ++k) {
    const double x = 40.0 * u(rng) * u(rng), y = 10.0 * u(rng);
    p.add(k, 0, x, y, u(rng) < 0.3 ? 0.5 : 0.125, 1.0, 1.0);
  }
  // Renumbered along x, as the World does (World::reorder_discs).
  std::vector<int> order(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) order[k] = k;
  std::sort(order.begin(), order.end(), [&](int a, int b) { return p.x[a] < p.x[b]; });
  Particles sorted;
  for (int k : order) sorted.add(k, 0, p.x[k], p.y[k], p.radius[k], 1.0, 1.0);
  Lists l;
  l.n = n;
  NeighborSearch search;
  search.rebuild(sorted, make_segments({{"floor", {{-1.0, 0.0}, {41.0, 0.0}}, true}}), 0.05, 1, {}, 1,
                 l.pairs, l.walls, l.runs);
  return l;
}

void expect_blocks(const std::vector<std::int64_t>& b, std::int64_t n, int threads) {
  ASSERT_EQ(b.size(), static_cast<std::size_t>(threads) + 1);
  EXPECT_EQ(b.front(), 0);
  EXPECT_EQ(b.back(), n);
  for (int t = 0; t < threads; ++t) {
    EXPECT_LE(b[t], b[t + 1]);
    if (b[t] < n) EXPECT_EQ(b[t] % DiscRuns::kWindow, 0) << "block " << t << " starts inside a window";
  }
}

std::int64_t contacts(const Lists& l, std::int64_t lo, std::int64_t hi) {
  return l.pairs.row_start[hi] + l.walls.row_start[hi] - l.pairs.row_start[lo] - l.walls.row_start[lo];
}

TEST(LoadBalance, FirstBlocksSplitTheEstimatedWorkEvenly) {
  const Lists l = heap(3000);
  for (int threads : {2, 3, 5}) {
    LoadBalance balance(LoadBalance::Work::contacts);
    balance.prepare(l.pairs, l.walls, l.runs, l.n, threads);
    const auto& b = balance.bounds();
    expect_blocks(b, l.n, threads);
    const double even = static_cast<double>(contacts(l, 0, l.n)) / threads;
    // Within the contacts of the windows at the block's two ends.
    for (int t = 0; t < threads; ++t)
      EXPECT_NEAR(static_cast<double>(contacts(l, b[t], b[t + 1])), even, 0.08 * even) << threads << " threads, block " << t;
    // The heap is denser on the left: equal disc counts would not be equal contacts.
    EXPECT_LT(b[1], l.n / threads);
  }
}

TEST(LoadBalance, BlocksFollowTheMeasuredSpeeds) {
  const Lists l = heap(3000);
  LoadBalance balance(LoadBalance::Work::contacts);
  balance.prepare(l.pairs, l.walls, l.runs, l.n, 2);
  // Thread 0 runs at half the speed of thread 1: each step it is busy twice as long per
  // contact. After some periods it holds a third of the contacts.
  const double speed[2] = {1.0, 2.0};
  for (int step = 0; step < 40 * LoadBalance::kPeriod; ++step) {
    const auto& b = balance.bounds();
    for (int t = 0; t < 2; ++t) balance.record(t, 1e-9 * static_cast<double>(contacts(l, b[t], b[t + 1])) / speed[t]);
    balance.after_step(l.pairs, l.walls, l.runs);
  }
  const auto& b = balance.bounds();
  expect_blocks(b, l.n, 2);
  const double share = static_cast<double>(contacts(l, 0, b[1])) / static_cast<double>(contacts(l, 0, l.n));
  EXPECT_NEAR(share, 1.0 / 3.0, 0.03);
  // Equal speeds bring it back to half.
  for (int step = 0; step < 40 * LoadBalance::kPeriod; ++step) {
    const auto& bb = balance.bounds();
    for (int t = 0; t < 2; ++t) balance.record(t, 1e-9 * static_cast<double>(contacts(l, bb[t], bb[t + 1])));
    balance.after_step(l.pairs, l.walls, l.runs);
  }
  const double back = static_cast<double>(contacts(l, 0, balance.bounds()[1])) / static_cast<double>(contacts(l, 0, l.n));
  EXPECT_NEAR(back, 0.5, 0.03);
}

TEST(LoadBalance, SpeedsJitteringByLessThanAWindowDoNotMoveTheBlocks) {
  const Lists l = heap(3000);
  LoadBalance balance(LoadBalance::Work::contacts);
  balance.prepare(l.pairs, l.walls, l.runs, l.n, 2);
  // Equal speeds, but thread 0 measured up to 4 % faster or slower in each period, as a shared
  // host does: the goal wanders by less than a window (~1 % of the work) either way, and no
  // end moves (a move costs more than a window gains, load_balance.cpp). Without the rule the
  // ends follow the noise.
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> noise(1 - 0.04, 1 + 0.04);
  const std::int64_t versions = balance.version();
  double factor = 1;
  for (int step = 0; step < 200 * LoadBalance::kPeriod; ++step) {
    if (step % LoadBalance::kPeriod == 0) factor = noise(rng);
    const auto& b = balance.bounds();
    for (int t = 0; t < 2; ++t)
      balance.record(t, 1e-9 * (t == 0 ? factor : 1.0) * static_cast<double>(contacts(l, b[t], b[t + 1])));
    balance.after_step(l.pairs, l.walls, l.runs);
  }
  EXPECT_EQ(balance.version(), versions) << "the blocks moved with the jitter";
  expect_blocks(balance.bounds(), l.n, 2);
}

TEST(LoadBalance, FewDiscsLeaveLaterBlocksEmptyAndNothingUncovered) {
  const Lists l = heap(40);  // two windows of lanes, four threads
  LoadBalance balance(LoadBalance::Work::sums);
  balance.prepare(l.pairs, l.walls, l.runs, l.n, 4);
  expect_blocks(balance.bounds(), l.n, 4);
  // An empty block has no speed to measure: the blocks stay whole and in order.
  for (int step = 0; step < 4 * LoadBalance::kPeriod; ++step) {
    const auto& b = balance.bounds();
    for (int t = 0; t < 4; ++t) balance.record(t, b[t + 1] > b[t] ? 1e-6 : 0.0);
    balance.after_step(l.pairs, l.walls, l.runs);
    expect_blocks(balance.bounds(), l.n, 4);
  }
}

}  // namespace
}  // namespace runout

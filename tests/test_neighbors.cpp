// Contact search and contact history (SPEC §2, §5): the cell grid + Verlet list finds exactly
// the brute-force pair set; history survives rebuilds; results do not depend on the skin or on
// the thread count (every per-disc sum runs in (i, j) order).
#include <omp.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <random>
#include <set>
#include <string>

#include "runout/neighbor_list.hpp"
#include "runout/setup.hpp"
#include "test_helpers.hpp"

namespace runout {
namespace {

Particles random_discs(int n, double box, double r_small, double r_large, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, box), coin(0.0, 1.0);
  Particles p;
  for (int k = 0; k < n; ++k) {
    // r_small < 0: radii spread evenly over [r_large / 5, r_large] (fine and coarse mixed).
    const double r = r_small < 0           ? r_large * (0.2 + 0.8 * coin(rng))
                     : coin(rng) < 0.3     ? r_large
                                           : r_small * (0.9 + 0.2 * coin(rng));
    p.add(k, 0, u(rng), u(rng), r, 1.0, 1.0);
  }
  return p;
}

TEST(NeighborSearch, FindsExactlyTheBruteForcePairs) {
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    for (double ratio : {1.0, 4.0, 8.33, 0.0}) {  // 0: a continuous spread of radii
      const Particles p = random_discs(1500, 30.0, ratio > 0 ? 0.5 / ratio : -1.0, 0.5, seed);
      const double skin = 0.05;
      const std::vector<Segment> walls = make_segments({{"w", {{0.0, 0.0}, {30.0, 5.0}, {30.0, 30.0}}, true}});
      // Equal shares for 1 and 2 threads, then the step's blocks of 2 (a window's end) and of
      // 3 (ends that start no window: every partition must give the same lists).
      const std::int64_t n = static_cast<std::int64_t>(p.size());
      const std::vector<std::vector<std::int64_t>> partitions = {{}, {}, {0, 352, n}, {0, 100, 1000, n}};
      for (std::size_t c = 0; c < partitions.size(); ++c) {
        const int threads = c == 0 ? 1 : partitions[c].empty() ? 2 : static_cast<int>(partitions[c].size()) - 1;
        NeighborSearch search;
        PairContacts pairs;
        WallContacts wall_pairs;
        DiscRuns runs;
        search.rebuild(p, walls, skin, threads, partitions[c], 1, pairs, wall_pairs, runs);
        std::set<std::pair<int, int>> found, expected;
        for (std::size_t q = 0; q < pairs.size(); ++q) found.insert({pairs.i[q], pairs.j[q]});
        for (std::size_t a = 0; a < p.size(); ++a)
          for (std::size_t b = a + 1; b < p.size(); ++b) {
            const double gap = std::hypot(p.x[b] - p.x[a], p.y[b] - p.y[a]) - p.radius[a] - p.radius[b];
            if (gap < skin) expected.insert({int(a), int(b)});
          }
        EXPECT_EQ(found, expected) << "seed " << seed << ", D/d " << ratio << ", threads " << threads;
        EXPECT_EQ(found.size(), pairs.size()) << "no duplicates";
        std::set<std::pair<int, int>> wall_found, wall_expected;
        for (std::size_t q = 0; q < wall_pairs.size(); ++q) wall_found.insert({wall_pairs.disc[q], wall_pairs.segment[q]});
        for (std::size_t a = 0; a < p.size(); ++a)
          for (std::size_t s = 0; s < walls.size(); ++s)
            if (distance_to(walls[s], {p.x[a], p.y[a]}) < p.radius[a] + skin) wall_expected.insert({int(a), int(s)});
        EXPECT_EQ(wall_found, wall_expected);
        // Each disc's run: the pairs where it is i (by j), then where it is j (by i), as
        // pushes on i at [q] and on j at [j_offset + q], in its lane of a slice (lane m of slice g
        // at slice_start[g] + L s + m for slot s), the slice as long as its longest run and the
        // padding reading the push that is always zero; every push read once. The lanes of a
        // window of kWindow discs are those discs, longest run first.
        constexpr std::int32_t L = DiscRuns::kSlice, W = DiscRuns::kWindow;
        const auto np = static_cast<std::int32_t>(pairs.size());
        std::vector<std::vector<std::int32_t>> expected_run(p.size()), run(p.size());
        for (std::int32_t q = 0; q < np; ++q) expected_run[pairs.i[q]].push_back(q);
        // The pushes on j, the zero push and the packed area each start a cache line after a
        // free one (8 doubles): np = 13 gives 24, 48 and 64.
        const auto on_j = static_cast<std::int32_t>(pairs.j_offset());
        EXPECT_EQ(on_j % 8, 0);
        EXPECT_GE(on_j, np + 8);
        EXPECT_LT(on_j, np + 16);
        EXPECT_EQ(pairs.zero_push() % 8, 0u);
        EXPECT_GE(pairs.zero_push(), pairs.j_offset() + np + 8);
        EXPECT_EQ(pairs.packed_area(), pairs.zero_push() + 16);
        EXPECT_EQ(PairContacts::after_a_free_line(13), 24u);
        EXPECT_EQ(PairContacts::after_a_free_line(16), 24u);
        EXPECT_EQ(PairContacts::after_a_free_line(0), 8u);
        for (std::int32_t q = 0; q < np; ++q) expected_run[pairs.j[q]].push_back(on_j + q);
        ASSERT_EQ(runs.slices(), (p.size() + L - 1) / L);
        ASSERT_EQ(runs.lane_disc.size(), runs.slices() * L);
        ASSERT_EQ(runs.source.size(), std::size_t(runs.slice_start.back()));
        std::vector<int> lanes_of(p.size(), 0);
        for (std::size_t m = 0; m < runs.lane_disc.size(); ++m) {
          const std::int32_t k = runs.lane_disc[m];
          if (m >= p.size()) { EXPECT_EQ(k, -1) << "lanes past the last disc are empty"; continue; }
          ASSERT_GE(k, 0);
          ASSERT_LT(std::size_t(k), p.size());
          ++lanes_of[k];
          EXPECT_EQ(std::size_t(k) / W, m / W) << "a disc stays in its window";
          if (m % W > 0)
            EXPECT_GE(expected_run[runs.lane_disc[m - 1]].size(), expected_run[k].size()) << "longest first";
        }
        EXPECT_EQ(lanes_of, std::vector<int>(p.size(), 1)) << "every disc in exactly one lane";
        for (std::size_t g = 0; g < runs.slices(); ++g) {
          const std::int32_t longest = (runs.slice_start[g + 1] - runs.slice_start[g]) / L;
          std::size_t expected_longest = 0;
          for (std::size_t m = g * L; m < (g + 1) * L; ++m) {
            const std::int32_t k = runs.lane_disc[m];
            if (k >= 0) expected_longest = std::max(expected_longest, expected_run[k].size());
            for (std::int32_t s = 0; s < longest; ++s) {
              const std::int32_t e = runs.source[runs.slice_start[g] + L * s + m % L];
              if (k >= 0 && std::size_t(s) < expected_run[k].size()) run[k].push_back(e);
              else EXPECT_EQ(e, std::int32_t(pairs.zero_push())) << "padding";
            }
          }
          EXPECT_EQ(std::size_t(longest), expected_longest);
        }
        EXPECT_EQ(run, expected_run);
        EXPECT_EQ(pairs.fx.size(), pairs.zero_push() + 1);
        EXPECT_EQ(pairs.fx[pairs.zero_push()], 0.0);
      }
    }
  }
}

// A rotation-locked disc held on a 20 degree slope by static friction (tan 20 < mu): its
// tangential spring carries m g sin(theta) on average (undamped, it rings about that value).
// Run once with a tiny skin and a second disc shooting past, which forces a rebuild every few
// steps, and once alone with a skin so wide that the list is never rebuilt: if a rebuild lost
// the history, the held disc's motion would differ.
std::vector<double> held_disc(double skin, bool with_flyer, std::int64_t& rebuilds,
                              double& mean_spring_force, double& expected) {
  const double theta = 20.0 * kPi / 180.0;
  SceneDef s;
  s.species = {{"disc", 0.5, 0.0, 0.0}};
  s.integration.skin = skin;
  s.walls = {{"slope", {{-50.0 * std::cos(theta), 50.0 * std::sin(theta)},
                        {50.0 * std::cos(theta), -50.0 * std::sin(theta)}}, true}};
  s.particles = {testing::disc(0.25 * std::sin(theta), 0.25 * std::cos(theta), 0.5)};
  if (with_flyer) s.particles.push_back(testing::disc(-40.0, 30.0, 0.5, 0, 20.0, 0.0));
  const SceneSetup setup = derive_setup(s);
  World w = build_explicit_world(s, setup, 1);
  Particles p = w.particles();
  p.inv_inertia[0] = 0.0;
  w = World(std::move(p), w.segments(), w.table(), w.settings());
  std::vector<double> xs;
  double sum = 0;
  int n = 0;
  const double k_s = w.table().wall[0].k_tangential;
  while (w.time() < 1.0) {
    w.step();
    xs.push_back(w.particles().x[0]);
    for (std::size_t q = 0; q < w.wall_contacts().size(); ++q)
      if (w.wall_contacts().disc[q] == 0) { sum += std::abs(w.wall_contacts().history[w.wall_contacts().size() + q]) * k_s; ++n; }  // columns: overlap_max, spring
  }
  rebuilds = w.profile().rebuilds;
  mean_spring_force = n ? sum / n : 0.0;
  expected = w.particles().mass[0] * 9.81 * std::sin(theta);
  return xs;
}

TEST(ContactHistory, SurvivesNeighbourListRebuilds) {
  std::int64_t rebuilds_often = 0, rebuilds_never = 0;
  double spring_often, spring_never, expected;
  const auto often = held_disc(0.01, true, rebuilds_often, spring_often, expected);
  const auto never = held_disc(20.0, false, rebuilds_never, spring_never, expected);
  EXPECT_GT(rebuilds_often, 100);
  EXPECT_EQ(rebuilds_never, 1);
  ASSERT_EQ(often.size(), never.size());
  for (std::size_t k = 0; k < often.size(); ++k) ASSERT_EQ(often[k], never[k]) << "step " << k;
  // Static friction holds the disc: the spring carries the slope's pull on average.
  EXPECT_NEAR(spring_often, expected, 0.02 * expected);
}

// The state after `t_star` of flow, with `threads` threads and the given skin.
World flowing(double skin, int threads, double t_star, bool ledger = false) {
  SceneDef s = testing::small_pile();
  s.integration.skin = skin;
  const SceneSetup setup = derive_setup(s);
  World w = build_settled_pile(s, setup, threads);
  release(w, setup);
  w.set_track_energy(ledger);
  while (w.time() < t_star * setup.unit_time) w.step();
  return w;
}

Particles flow(double skin, int threads, double t_star) { return flowing(skin, threads, t_star).particles(); }

void expect_identical(const Particles& a, const Particles& b, const char* what) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    ASSERT_EQ(a.x[k], b.x[k]) << what << ": disc " << k;
    ASSERT_EQ(a.y[k], b.y[k]) << what << ": disc " << k;
    ASSERT_EQ(a.omega[k], b.omega[k]) << what << ": disc " << k;
  }
}

TEST(Determinism, BitIdenticalAcrossThreadCounts) {
  expect_identical(flow(0.2, 1, 3.0), flow(0.2, 2, 3.0), "1 vs 2 threads");
}

// OpenMP may give a smaller team than asked (OMP_THREAD_LIMIT=1 in the environment, or a run
// started inside another parallel region): every block of the lists and of the step must still
// be computed, by the threads there are, to the same bits.
// With the ledger on, the one thread carries every block's losses and books each pass once.
TEST(Determinism, BitIdenticalWhenOpenMPGivesFewerThreadsThanAsked) {
  const World one = flowing(0.2, 1, 2.0, true);
  struct OneThreadTeams {  // no region is active, so every team has one thread
    int levels = omp_get_max_active_levels();
    OneThreadTeams() { omp_set_max_active_levels(0); }
    ~OneThreadTeams() { omp_set_max_active_levels(levels); }
  };
  std::optional<World> limited;
  {
    const OneThreadTeams guard;
    int team = 0;
#pragma omp parallel num_threads(2)
    team = omp_get_num_threads();
    ASSERT_EQ(team, 1) << "the test's premise: OpenMP gives one thread of two asked";
    limited.emplace(flowing(0.2, 2, 2.0, true));
  }
  expect_identical(one.particles(), limited->particles(), "1 thread vs 2 asked and 1 given");
  EXPECT_GT(one.dissipation().normal, 0.0);
  EXPECT_GT(one.dissipation().friction, 0.0);
  EXPECT_EQ(limited->dissipation().normal, one.dissipation().normal);
  EXPECT_EQ(limited->dissipation().friction, one.dissipation().friction);
}

// Fewer discs than a window of lanes, and not a whole slice: the second thread's block is
// empty and starts inside the first thread's slice. Two discs roll into each other on a floor;
// the run is repeated, as a race shows only now and then.
TEST(Determinism, BitIdenticalAcrossThreadCountsWithFewDiscs) {
  SceneDef s;
  s.species = {{"disc", 0.5, 0.0, 0.0}};
  s.walls = {WallDef{"floor", {{-5.0, 0.0}, {5.0, 0.0}}, true, WallInside::left}};
  s.particles = {testing::disc(-1.0, 0.25, 0.5, 0, 1.0), testing::disc(1.0, 0.25, 0.5, 0, -1.0),
                 testing::disc(3.0, 0.25, 0.5, 0, -0.5)};
  const SceneSetup setup = derive_setup(s);
  auto run = [&](int threads) {
    World w = build_explicit_world(s, setup, threads);
    w.set_track_energy(true);
    while (w.time() < 1.5 * setup.unit_time) w.step();
    return w.particles();
  };
  const Particles one = run(1);
  for (int repeat = 0; repeat < 20; ++repeat) expect_identical(one, run(2), "1 vs 2 threads, 3 discs");
}

// Steps `w` until `until` seconds, checking by brute force over every pair and wall segment
// that the lists hold every contact whenever a step uses them without a rebuild (SPEC §5,
// ListDrift). Returns how many steps used lists built at an earlier step.
std::int64_t check_lists_hold_every_contact(World& w, double until, const char* what) {
  std::int64_t used = 0;
  while (w.time() < until) {
    const Particles& p = w.particles();
    std::vector<std::pair<std::int32_t, std::int32_t>> touching, walls;
    for (std::int32_t i = 0; i < static_cast<std::int32_t>(p.size()); ++i) {
      for (std::int32_t j = i + 1; j < static_cast<std::int32_t>(p.size()); ++j)
        if (std::hypot(p.x[j] - p.x[i], p.y[j] - p.y[i]) < p.radius[i] + p.radius[j]) touching.push_back({i, j});
      for (std::int32_t g = 0; g < static_cast<std::int32_t>(w.segments().size()); ++g) {
        const Segment& seg = w.segments()[g];
        const WallTouch t = wall_touch(seg, {p.x[i], p.y[i]}, p.radius[i]);
        if (seg.active && t.acts && t.gap < p.radius[i]) walls.push_back({i, g});
      }
    }
    const PairContacts pairs = w.pairs();
    const WallContacts wall_lists = w.wall_contacts();
    const std::int64_t rebuilds = w.profile().rebuilds;
    w.step();
    if (w.profile().rebuilds != rebuilds) continue;  // the step built new lists first
    ++used;
    for (const auto& [i, j] : touching) {
      const auto row = pairs.j.begin() + pairs.row_start[i], end = pairs.j.begin() + pairs.row_start[i + 1];
      if (!std::binary_search(row, end, j))
        ADD_FAILURE() << what << ": pair " << i << "-" << j << " unlisted at step " << w.step_count();
    }
    for (const auto& [i, g] : walls) {
      const auto row = wall_lists.segment.begin() + wall_lists.row_start[i];
      const auto end = wall_lists.segment.begin() + wall_lists.row_start[i + 1];
      if (std::find(row, end, g) == end)
        ADD_FAILURE() << what << ": disc " << i << ", segment " << g << " unlisted at step " << w.step_count();
    }
    if (::testing::Test::HasFailure()) break;
  }
  return used;
}

// At 2 threads each thread measures its own groups' displacements (World::forces_and_motion).
TEST(NeighborLists, HoldEveryContactOfAFlow) {
  for (int threads : {1, 2})
    for (double skin : {0.05, 0.3}) {
      SceneDef s = testing::small_pile();
      s.integration.skin = skin;
      const SceneSetup setup = derive_setup(s);
      World w = build_settled_pile(s, setup, threads);
      release(w, setup);
      const std::string what = "skin " + std::to_string(skin) + ", threads " + std::to_string(threads);
      EXPECT_GT(check_lists_hold_every_contact(w, 3.0 * setup.unit_time, what.c_str()), 100);
    }
}

// The lists' test gives the same answer whoever measures which discs: the same rebuilds at 1
// and 2 threads (at 2 each thread measures its own groups once the whole flow's bound is spent).
TEST(NeighborLists, RebuildAtTheSameStepsAtOneAndTwoThreads) {
  SceneDef s = testing::small_pile();
  s.avalanche = testing::short_avalanche(12.0, 8.0, 30.0, 40.0, 150);  // a few hundred discs
  const SceneSetup setup = derive_setup(s);
  std::vector<std::int64_t> rebuilt_at[2];
  for (int threads : {1, 2}) {
    World w = build_settled_pile(s, setup, threads);
    release(w, setup);
    std::int64_t rebuilds = w.profile().rebuilds;
    while (w.time() < 3.0 * setup.unit_time) {
      w.step();
      if (w.profile().rebuilds != rebuilds) rebuilt_at[threads - 1].push_back(w.step_count());
      rebuilds = w.profile().rebuilds;
    }
  }
  EXPECT_GT(rebuilt_at[0].size(), 10u);
  EXPECT_EQ(rebuilt_at[0], rebuilt_at[1]);
}

// A lone disc slides over the floor's joint into the end wall, and another flies into it: only
// the walls' margins can call the rebuilds (a lone disc's spread is zero).
TEST(NeighborLists, HoldEveryWallContactOfALoneDisc) {
  for (const ParticleDef& lone : {testing::disc(5.0, 0.25, 0.5, 0, -3.0), testing::disc(-2.0, 0.25, 0.5, 0, 3.0),
                                  testing::disc(6.0, 3.0, 0.5, 0, 4.0, 1.0)}) {
    SceneDef s;
    s.species = {{"disc", 0.5, 0.0, 0.0}};
    s.walls = {WallDef{"floor", {{-10.0, 0.0}, {0.0, 0.0}, {10.0, 0.0}}, true, WallInside::left},
               WallDef{"end", {{10.0, 0.0}, {10.0, 6.0}}, false, WallInside::both}};
    s.particles = {lone};
    const SceneSetup setup = derive_setup(s);
    World w = build_explicit_world(s, setup, 1);
    EXPECT_GT(check_lists_hold_every_contact(w, 2.5, "lone disc"), 100);
    EXPECT_GT(w.profile().rebuilds, 2);
  }
}

TEST(Determinism, BitIdenticalAcrossSkins) {
  // A pair out of contact adds exactly zero, and contacts are summed in (i, j) order whatever
  // else the list holds: the skin changes the cost, never the trajectory.
  expect_identical(flow(0.1, 1, 3.0), flow(0.4, 1, 3.0), "skin 0.1 vs 0.4");
}

}  // namespace
}  // namespace runout

namespace runout {
namespace {

// Renumbering moves discs in the arrays; every disc must keep its own size and mass.
TEST(Renumbering, SettledPileKeepsEachDiscsSize) {
  SceneDef s = testing::small_pile();
  s.species[0].spread = s.species[1].spread = 0.0;
  const SceneSetup setup = derive_setup(s);
  const World w = build_settled_pile(s, setup, 1);
  const auto& p = w.particles();
  ASSERT_GT(w.step_count(), 2000) << "settling must outlast one renumbering";
  for (std::size_t k = 0; k < p.size(); ++k) {
    const double nominal = 0.5 * s.species[p.species[k]].diameter;
    EXPECT_DOUBLE_EQ(p.radius[k], nominal) << "disc id " << p.id[k];
    EXPECT_DOUBLE_EQ(p.mass[k], sphere_mass(nominal, s.material.density)) << "disc id " << p.id[k];
  }
}

// Discs are numbered along x (World::reorder_discs), also where explicit discs lie as far apart
// as a scene allows (coordinates up to 1e9 m from the origin) and are a millimetre wide: strips
// of 0.01 r_max would number 4e14 of them, and the packed sort key would overflow.
TEST(Renumbering, DiscsFarApartAreNumberedAlongX) {
  SceneDef s;
  s.species = {{"disc", 0.001, 0.0, 0.0}};
  for (double x : {9e8, -9e8, 0.0, 4e8, -3e8, 1e3, -7e8, 2e8})
    s.particles.push_back(testing::disc(x, 0.0, 0.001));
  const SceneSetup setup = derive_setup(s);
  const World built = build_explicit_world(s, setup, 1);
  StepSettings st = built.settings();
  st.reorder_every = 1;
  World w(built.particles(), built.segments(), built.table(), st);
  w.step();
  const auto& p = w.particles();
  for (std::size_t k = 1; k < p.size(); ++k)
    EXPECT_LT(p.x[k - 1], p.x[k]) << "discs " << p.id[k - 1] << " and " << p.id[k] << " out of order";
}

}  // namespace
}  // namespace runout

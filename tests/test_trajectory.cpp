// The trajectory hash: a small thesis-like pile (test_helpers.hpp small_pile: D/d = 2, 30 large
// discs' area) settled from its seed, released and run to t* = 2 with the default laws, at 1 and
// 2 threads; every disc's position, velocity, spin and angle, bit for bit, hashed (FNV-1a).
// The stored value (tests/golden/trajectory_hash.txt) is also the physics part of the pile
// cache's key (apps/prepare.cpp): a change that moves any trajectory fails this test, and
// regenerating the hash (RUNOUT_UPDATE_GOLDENS=1, on purpose, saying why in the commit)
// retires every cached pile the old physics settled.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include "runout/io/files.hpp"
#include "runout/run.hpp"
#include "runout/setup.hpp"
#include "test_helpers.hpp"

namespace runout {
namespace {

std::string trajectory_hash(int threads) {
  SceneDef s = testing::small_pile();
  s.output.end_time = 2.0;
  const SceneSetup setup = derive_setup(s);
  World w = build_settled_pile(s, setup, threads);
  release(w, setup);
  AvalancheRun run(w, s, setup);
  run.run();
  const Particles& p = w.particles();
  std::uint64_t h = io::fnv1a64("");
  for (const auto* v : {&p.x, &p.y, &p.vx, &p.vy, &p.omega, &p.angle})
    h = io::fnv1a64(std::string_view(reinterpret_cast<const char*>(v->data()), v->size() * sizeof(double)), h);
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

TEST(Trajectory, SmallPileHashIsTheStoredOneAtOneAndTwoThreads) {
  const std::string path = std::string(RUNOUT_SOURCE_DIR) + "/tests/golden/trajectory_hash.txt";
  const std::string one = trajectory_hash(1), two = trajectory_hash(2);
  EXPECT_EQ(one, two) << "the trajectory depends on the thread count";
  if (const char* u = std::getenv("RUNOUT_UPDATE_GOLDENS"); u && std::string(u) == "1") {
    std::ofstream(path) << one << "\n";
    GTEST_SKIP() << "wrote " << path;
  }
  std::ifstream in(path);
  std::string stored;
  ASSERT_TRUE(in >> stored) << path << " is missing (RUNOUT_UPDATE_GOLDENS=1 writes it)";
  EXPECT_EQ(one, stored) << "the physics changed: if on purpose, regenerate " << path;
}

// A settled pile of `scene`, released (prepared with two threads).
World released_pile(const SceneDef& scene) {
  const SceneSetup setup = derive_setup(scene);
  World w = build_settled_pile(scene, setup, 2);
  release(w, setup);
  return w;
}

// Whether two worlds' discs have the same bits of position, velocity and spin.
::testing::AssertionResult same_disc_state(const World& a, const World& b) {
  const std::pair<const char*, HotArray<double> Particles::*> members[] = {
      {"x", &Particles::x}, {"y", &Particles::y}, {"vx", &Particles::vx},
      {"vy", &Particles::vy}, {"omega", &Particles::omega}};
  for (const auto& [name, member] : members)
    if (a.particles().*member != b.particles().*member)
      return ::testing::AssertionFailure() << "the discs' " << name << " differ";
  return ::testing::AssertionSuccess();
}

// Steps `one` at one thread and `other` as `threads_at(step)` says, 300 steps, and checks
// their discs have the same bits and have moved.
template <class ThreadsAt>
void expect_steps_like_one(const World& released, const ThreadsAt& threads_at) {
  World one = released, other = released;
  one.set_threads(1);
  for (int k = 0; k < 300; ++k) {
    if (const int t = threads_at(k); t > 0) {
      other.set_threads(t);
      ASSERT_EQ(other.settings().threads, t);
    }
    one.step();
    other.step();
  }
  EXPECT_TRUE(same_disc_state(one, other));
  EXPECT_NE(other.particles().x, released.particles().x);  // the pile moved
}

// More threads than World keeps block outcomes for on the stack (8): the same bits as one.
// The world is stepped directly (a run's thread governor may drop threads that take turns on
// a 2-core machine), from the released small pile, for 300 steps.
TEST(Trajectory, NineThreadsStepLikeOne) {
  expect_steps_like_one(released_pile(testing::small_pile()), [](int k) { return k == 0 ? 9 : 0; });
}

// A run whose thread count changes between steps (bench --against-threads, a resumed run's
// governor) steps like one thread throughout: passes of several threads point the discs' sums
// at a packed copy of the crossing pushes (Handoff), and a pass of one thread must read them
// in place again. 300 steps from a released pile of ~300 discs: 2, 1, 3, then 1 thread.
TEST(Trajectory, ThreadCountChangedBetweenStepsStepsLikeOne) {
  expect_steps_like_one(released_pile(testing::medium_pile()), [](int k) {
    return k % 75 != 0 ? 0 : k == 0 ? 2 : k == 150 ? 3 : 1;
  });
}

// A world assigned over one that has stepped at several threads counts its passes from the
// assigned world's count again. The threads' ready flags must start again too: a flag left
// at a pass the new world reaches later would let a later block skip its wait for an earlier
// one. Each cycle leaves flags 2-8 at the pass where 9 threads come back; a skipped wait is a
// race, so the cycle is repeated (without the reset, 2 of 5 single cycles failed).
TEST(Trajectory, WorldAssignedOverASteppedOneStepsLikeOne) {
  const World released = released_pile(testing::medium_pile());
  constexpr int kSteps = 20, kAfter = 5, kCycles = 10;
  World one = released;
  one.set_threads(1);
  for (int k = 0; k < kSteps + kAfter; ++k) one.step();
  World other = released;
  for (int cycle = 0; cycle < kCycles; ++cycle) {
    other = released;
    other.set_threads(9);
    for (int k = 0; k < kSteps; ++k) other.step();
    other = released;
    other.set_threads(2);
    for (int k = 0; k < kSteps - 1; ++k) other.step();
    other.set_threads(9);
    for (int k = 0; k < kAfter + 1; ++k) other.step();
    ASSERT_TRUE(same_disc_state(one, other)) << "cycle " << cycle;
  }
}

// Many steps in one advance: two threads keep one parallel region across steps until the
// lists must be rebuilt or the blocks move, judging each step alike (World::advance). The
// same bits as one thread stepping one step at a time: positions, velocities, spins, the
// clock, the rebuilds and, with the ledger on, every joule of dissipation (each region
// step's ledger is read while the next one's is written). 3000 steps of a flowing pile cross several rebuilds.
TEST(Trajectory, AdvanceOfManyStepsStepsLikeOneStepAtATime) {
  World released = released_pile(testing::medium_pile());
  released.set_track_energy(true);
  constexpr int kSteps = 3000;
  World one = released;
  one.set_threads(1);
  for (int k = 0; k < kSteps; ++k) one.step();
  const std::int64_t one_rebuilt = one.profile().rebuilds - released.profile().rebuilds;
  // A step's forces started before the verdict on the step before, and dropped where that
  // verdict ends the region (`always`: at every rebuild and every first spent bound), leave
  // no trace: not in the history (the friction springs), the ledger or the rebuilds.
  using Ahead = StepSettings::Ahead;
  for (const Ahead ahead : {Ahead::when_safe, Ahead::always, Ahead::never})
    for (const int threads : {2, 9}) {
      World other = released;
      other.set_threads(threads);
      other.set_ahead(ahead);
      const StepProfile before = other.profile();
      other.advance(kSteps);
      const StepProfile after = other.profile();
      const std::string what = std::to_string(threads) + " threads, ahead " + std::to_string(static_cast<int>(ahead));
      EXPECT_GE(after.rebuilds - before.rebuilds, 3) << "the flow should cross several rebuilds";
      // The groups' bound, judged inside the region from each block's terms, is the one a
      // thread alone works out: the lists are rebuilt as often.
      EXPECT_EQ(after.rebuilds - before.rebuilds, one_rebuilt) << what;
      EXPECT_TRUE(same_disc_state(one, other)) << what;
      EXPECT_EQ(other.step_count(), one.step_count());
      EXPECT_EQ(other.time(), one.time());
      EXPECT_EQ(other.dissipation().normal, one.dissipation().normal) << what;
      EXPECT_EQ(other.dissipation().friction, one.dissipation().friction) << what;
      EXPECT_GT(other.dissipation().normal + other.dissipation().friction, 0.0);
      const std::int64_t ahead_steps = after.steps_ahead - before.steps_ahead;
      const std::int64_t dropped = after.steps_dropped - before.steps_dropped;
      if (ahead == Ahead::never) EXPECT_EQ(ahead_steps, 0) << what;
      else EXPECT_GT(ahead_steps, kSteps / 4) << what;
      if (ahead == Ahead::always) EXPECT_GT(dropped, 0) << what;
      if (ahead == Ahead::when_safe) EXPECT_LE(dropped, ahead_steps / 50) << what;
    }
}

}  // namespace
}  // namespace runout

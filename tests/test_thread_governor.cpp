// The thread governor against a machine whose cores are taken and given back on a known
// schedule (a fake clock: wall time advances a fixed amount per call, the process's CPU time
// by that times the threads that get a core), and a run that follows it bit for bit.
#include <gtest/gtest.h>

#include <algorithm>

#include "runout/run.hpp"
#include "runout/setup.hpp"
#include "runout/thread_governor.hpp"
#include "test_helpers.hpp"

namespace runout {
namespace {

// A two-core machine on which another program holds one core while `taken(wall)` is true.
// The process's CPU time grows by the cores its threads get: all of them alone; beside the
// other program, the scheduler shares the cores, so `threads` runnable threads get
// 2 · threads / (threads + 1) cores (1.33 for two, 1.0 for one).
struct FakeMachine {
  double step = 0.01;  // wall seconds between calls
  std::function<bool(double)> taken;
  int threads = 2;
  ThreadGovernor::Usage now;
  ThreadGovernor::Usage tick() {
    const double cores = taken(now.wall_seconds) ? 2.0 * threads / (threads + 1) : threads;
    now.wall_seconds += step;
    now.cpu_seconds += step * cores;
    return now;
  }
};

// Runs the governor for `seconds` of fake wall time; the thread count at each call.
std::vector<int> follow(FakeMachine& m, ThreadGovernor& g, double seconds) {
  std::vector<int> counts;
  while (m.now.wall_seconds < seconds) {
    m.threads = g.advise(m.threads);
    counts.push_back(m.threads);
  }
  return counts;
}

TEST(ThreadGovernor, KeepsEveryThreadWhileTheCoresAreFree) {
  FakeMachine m;
  m.taken = [](double) { return false; };
  ThreadGovernor g(2, 1.0, 30.0, [&] { return m.tick(); });
  const auto counts = follow(m, g, 100.0);
  EXPECT_TRUE(std::all_of(counts.begin(), counts.end(), [](int t) { return t == 2; }));
  EXPECT_NEAR(g.last_cores_used(), 2.0, 1e-9);
}

TEST(ThreadGovernor, DropsToTheCoresItGetsAndTakesThemBackOnceFree) {
  // Another program holds a core from 5 s to 65 s.
  FakeMachine m;
  m.taken = [](double t) { return t >= 5.0 && t < 65.0; };
  ThreadGovernor g(2, 1.0, 30.0, [&] { return m.tick(); });
  const auto counts = follow(m, g, 120.0);
  auto at = [&](double t) { return counts[static_cast<std::size_t>(t / m.step)]; };
  EXPECT_EQ(at(4.0), 2);
  // The first two whole windows beside the other program show 1.33 of 2 cores, below
  // 0.75 · 2: one thread from the second one's end (7 or 8 s) on.
  EXPECT_EQ(at(8.5), 1);
  EXPECT_EQ(at(30.0), 1);
  // 30 s after the drop it tries two threads for a window, finds 1.33 cores, drops again.
  int tries_while_taken = 0;
  for (std::size_t k = 1; k < counts.size(); ++k)
    if (counts[k] == 2 && counts[k - 1] == 1 && k * m.step < 65.0) ++tries_while_taken;
  EXPECT_EQ(tries_while_taken, 1);  // at about 38 s; the next one (about 70 s) finds the core free
  EXPECT_EQ(at(60.0), 1);
  // Free again from 65 s: the try after it keeps both threads for good.
  EXPECT_EQ(at(100.0), 2);
  EXPECT_EQ(at(119.0), 2);
}

TEST(ThreadGovernor, OneShortWindowIsNotContention) {
  // The host holds a core for 1.2 s (one whole window and a fifth of the next): no drop.
  FakeMachine m;
  m.taken = [](double t) { return t >= 10.0 && t < 11.2; };
  ThreadGovernor g(2, 1.0, 30.0, [&] { return m.tick(); });
  const auto counts = follow(m, g, 40.0);
  EXPECT_TRUE(std::all_of(counts.begin(), counts.end(), [](int t) { return t == 2; }));
}

TEST(ThreadGovernor, ItsOwnIdleThreadsAreNotContention) {
  // The run leaves 0.7 of its two cores idle itself (serial work, its other thread parked):
  // the machine has idle cores, so nobody else took them.
  ThreadGovernor::Usage c;
  ThreadGovernor g(2, 1.0, 30.0, [&] {
    c.wall_seconds += 0.1; c.cpu_seconds += 0.1 * 1.3; c.idle_seconds += 0.1 * 0.7;
    return c;
  });
  int t = 2;
  for (int k = 0; k < 100; ++k) t = g.advise(t);
  EXPECT_EQ(t, 2);
  EXPECT_NEAR(g.last_cores_used(), 1.3, 1e-9);
}

TEST(ThreadGovernor, NeverGoesBelowOneOrAboveMost) {
  FakeMachine m;
  m.taken = [](double) { return true; };
  ThreadGovernor one(1, 1.0, 30.0, [&] { return m.tick(); });
  m.threads = 1;
  for (int k = 0; k < 1000; ++k) ASSERT_EQ(one.advise(1), 1);
  // Eight threads on a machine that gives the process 3.2 cores: three threads.
  ThreadGovernor::Usage c;
  ThreadGovernor eight(8, 1.0, 30.0, [&] { c.wall_seconds += 0.1; c.cpu_seconds += 0.1 * 3.2; return c; });
  int t = 8;
  for (int k = 0; k < 40; ++k) t = eight.advise(t);
  EXPECT_EQ(t, 3);
  EXPECT_NEAR(eight.last_cores_used(), 3.2, 1e-9);
}

// A run whose governor drops it to one thread midway and back to two gives the same
// trajectory, bit for bit, as a run on one thread throughout.
TEST(ThreadGovernor, ARunThatChangesItsThreadsFollowsTheSameTrajectory) {
  SceneDef s = testing::small_pile();
  s.output.end_time = 1.5;
  const SceneSetup setup = derive_setup(s);
  int calls_at[3] = {0, 0, 0};  // the world's thread count when the governor is asked
  auto final_state = [&](int threads, bool governed, std::vector<int>* seen) {
    World w = build_settled_pile(s, setup, threads);
    release(w, setup);
    AvalancheRun run(w, s, setup);
    // The run asks about 20 times per t*. Fake wall time: 0.05 s per call; one core is taken
    // from the 5th to the 15th call; windows of 0.1 s, a retry 0.3 s after a drop.
    int calls = 0;
    ThreadGovernor::Usage c;
    ThreadGovernor g(2, 0.1, 0.3, [&] {
      ++calls;
      if (governed) ++calls_at[std::min(w.settings().threads, 2)];
      const double cores = calls >= 5 && calls < 15 ? 1.0 : w.settings().threads;
      c.wall_seconds += 0.05;
      c.cpu_seconds += 0.05 * cores;
      return c;
    });
    if (governed)
      run.set_thread_governor(&g, [&](double, int now, double) { if (seen) seen->push_back(now); });
    const RunResult r = run.run();
    EXPECT_EQ(r.fewest_threads, governed ? 1 : threads);
    return w.particles();
  };
  std::vector<int> changes;
  const Particles governed = final_state(2, true, &changes);
  ASSERT_GE(changes.size(), 2u) << "the governor never changed the thread count";
  EXPECT_EQ(changes.front(), 1);
  EXPECT_EQ(changes.back(), 2);
  EXPECT_GT(calls_at[1], 3) << "the world did not step on one thread";
  EXPECT_GT(calls_at[2], 3) << "the world did not step on two threads";
  const Particles one = final_state(1, false, nullptr);
  ASSERT_EQ(governed.size(), one.size());
  for (std::size_t k = 0; k < one.size(); ++k) {
    ASSERT_EQ(governed.x[k], one.x[k]) << "disc " << k;
    ASSERT_EQ(governed.y[k], one.y[k]) << "disc " << k;
    ASSERT_EQ(governed.vx[k], one.vx[k]) << "disc " << k;
    ASSERT_EQ(governed.omega[k], one.omega[k]) << "disc " << k;
  }
}

}  // namespace
}  // namespace runout

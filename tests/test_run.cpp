// The run loop: the at-rest criterion and observer scheduling.
#include <gtest/gtest.h>
#include <omp.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <set>
#include <thread>

#include <cmath>
#include <cstring>

#include <nlohmann/json.hpp>

#include "runout/checkpoint.hpp"
#include "runout/errors.hpp"
#include "runout/io/outputs.hpp"
#include "runout/run.hpp"
#include "runout/setup.hpp"
#include "test_helpers.hpp"

namespace runout {
namespace {

SceneDef floor_scene() {
  SceneDef s;
  s.species = {{"disc", 0.5, 0.0, 0.0}};
  s.walls = {{"floor", {{-50.0, 0.0}, {5000.0, 0.0}}, true}};
  return s;
}

// Two discs squeezed side by side in a pit (they stay in contact: the mass) and one rolling
// away: with no rolling resistance the lone disc rolls for ever at its initial speed, yet the
// mass comes to rest and the run ends.
TEST(Run, LoneRollingDiscDoesNotKeepTheMassMoving) {
  SceneDef s = floor_scene();
  s.walls.push_back({"pit_left", {{-0.25, 1.0}, {-0.25, 0.0}}, false});
  s.walls.push_back({"pit_right", {{0.749, 0.0}, {0.749, 1.0}}, false});
  s.particles = {testing::disc(0.0, 0.25, 0.5), testing::disc(0.4995, 0.25, 0.5),
                 testing::disc(5.0, 0.25, 0.5, 0, 1.0, 0.0, -4.0)};  // v = -omega r: rolling
  s.rest.max_time = 300.0;
  const SceneSetup setup = derive_setup(s);
  World w = build_explicit_world(s, setup, 1);
  AvalancheRun run(w, s, setup);
  const RunResult r = run.run();
  EXPECT_TRUE(r.at_rest);
  EXPECT_LT(r.t_star_end, 100.0);
  EXPECT_NEAR(w.particles().vx[2], 1.0, 1e-3);  // still rolling: no rolling resistance
  const auto& p = w.particles();
  EXPECT_LT(std::hypot(p.x[1] - p.x[0], p.y[1] - p.y[0]), 0.5) << "the pair must stay in contact";
}

SceneDef pit_and_roller() {
  SceneDef s = floor_scene();
  s.walls.push_back({"pit_left", {{-0.25, 1.0}, {-0.25, 0.0}}, false});
  s.walls.push_back({"pit_right", {{0.749, 0.0}, {0.749, 1.0}}, false});
  s.particles = {testing::disc(0.0, 0.25, 0.5), testing::disc(0.4995, 0.25, 0.5),
                 testing::disc(5.0, 0.25, 0.5, 0, 1.0, 0.0, -4.0)};
  s.rest.max_time = 300.0;
  return s;
}

// A run that goes on after rest (for a later snapshot) reports the deposit as it was when the
// mass came to rest: the lone roller keeps moving the centre of mass, yet mu is the same as
// in the run that stopped at rest — also across a checkpoint taken after rest.
TEST(Run, GoingOnAfterRestDoesNotChangeTheMeasurements) {
  const SceneDef s = pit_and_roller();
  const SceneSetup setup = derive_setup(s);
  World a = build_explicit_world(s, setup, 1);
  AvalancheRun at_rest(a, s, setup);
  const RunResult ra = at_rest.run();
  ASSERT_TRUE(ra.at_rest);

  const double later = ra.t_star_end + 40.0;
  World b = build_explicit_world(s, setup, 1);
  SceneDef first_part = s;
  first_part.output.end_time = ra.t_star_end + 20.0;  // stop (a checkpoint) after rest ...
  AvalancheRun run_b(b, first_part, setup);
  run_b.set_min_end_time(later);
  run_b.run();
  const RunState saved = decode_run_state(encode_run_state(run_b.state()), "state");
  AvalancheRun resumed(b, s, setup, saved);  // ... and resume to the later snapshot
  resumed.set_min_end_time(later);
  const RunResult rb = resumed.run();

  EXPECT_NEAR(rb.t_star_end, later, 0.1);
  EXPECT_TRUE(rb.at_rest);
  EXPECT_EQ(rb.t_star_rest, ra.t_star_rest);
  EXPECT_EQ(rb.mu_global, ra.mu_global);
  EXPECT_EQ(rb.L_cm, ra.L_cm);
  EXPECT_EQ(rb.com_rest.x(), ra.com_rest.x());
  EXPECT_EQ(rb.final_energy.x_cm, ra.final_energy.x_cm);
  // The roller did move on: measured at the end, the centre of mass (three equal discs) would
  // be a third of the roller's 40 t* at 1 m/s further.
  const double roller_travel = (rb.t_star_end - ra.t_star_end) * setup.unit_time * 1.0;
  EXPECT_NEAR(centre_of_mass(b.particles()).x() - rb.com_rest.x(), roller_travel / 3.0, 0.01);
}

// The ledger counts losses from release on: a run started without it cannot be resumed with
// it (the losses before the checkpoint are unknown), and says so.
TEST(Run, LedgerCannotStartAtAResume) {
  SceneDef bare = pit_and_roller();
  bare.output.series.energy = false;
  bare.output.end_time = 2.0;
  const SceneSetup setup = derive_setup(bare);
  World w = build_explicit_world(bare, setup, 1);
  AvalancheRun first(w, bare, setup);
  first.run();
  const RunState saved = decode_run_state(encode_run_state(first.state()), "state");
  const SceneDef full = pit_and_roller();
  try {
    AvalancheRun resumed(w, full, setup, saved);
    FAIL() << "a resume switched the ledger on midway";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("output.series"), std::string::npos) << e.what();
  }
  // The same selection resumes, and to the same end as a run never stopped.
  SceneDef longer = bare;
  longer.output.end_time = 3.0;
  AvalancheRun resumed_bare(w, longer, setup, saved);
  const RunResult r = resumed_bare.run();
  World u = build_explicit_world(longer, setup, 1);
  AvalancheRun whole(u, longer, setup);
  const RunResult ru = whole.run();
  EXPECT_EQ(r.t_star_end, ru.t_star_end);
  EXPECT_EQ(w.particles().x, u.particles().x);
  EXPECT_EQ(w.particles().omega, u.particles().omega);
}

class Recorder : public Observer {
 public:
  void observe(const World&, const RunState&, double t_star) override { times.push_back(t_star); }
  std::vector<double> times;
};

// One disc on the floor to t* = 3 with the given observers; also half a step in t*.
std::pair<RunResult, double> disc_on_floor(const std::vector<std::pair<Observer*, Schedule>>& observers) {
  SceneDef s = floor_scene();
  s.particles = {testing::disc(0.0, 0.3, 0.5)};
  s.output.end_time = 3.0;
  const SceneSetup setup = derive_setup(s);
  World w = build_explicit_world(s, setup, 1);
  AvalancheRun run(w, s, setup);
  for (const auto& [observer, schedule] : observers) run.add_observer(*observer, schedule);
  return {run.run(), 0.5 * setup.dt / setup.unit_time};
}

TEST(Run, ObserversFireOnTheNearestStep) {
  Recorder every, at;
  const auto [r, half_step] = disc_on_floor({{&every, {1.0, 0.0, {}}}, {&at, {0.0, 0.0, {0.25, 2.5}}}});
  EXPECT_TRUE(r.reached_end_time);  // even if t* ends up to half a step before 3
  ASSERT_EQ(every.times.size(), 4u);  // 0, 1, 2, 3
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(every.times[k], k, half_step + 1e-12);
  ASSERT_EQ(at.times.size(), 2u);
  EXPECT_NEAR(at.times[0], 0.25, half_step + 1e-12);
  EXPECT_NEAR(at.times[1], 2.5, half_step + 1e-12);
}

// What observers cost the run is reported: an observer that takes 20 ms a call, called 4 times.
class SlowRecorder : public Observer {
 public:
  void observe(const World&, const RunState&, double) override {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    ++calls;
  }
  int calls = 0;
};

TEST(Run, TheTimeSpentInObserversIsReported) {
  SlowRecorder slow;
  const RunResult r = disc_on_floor({{&slow, {1.0, 0.0, {}}}}).first;
  ASSERT_EQ(slow.calls, 4);
  EXPECT_GE(r.observer_seconds, 0.080);
  EXPECT_LE(r.observer_seconds, r.wall_seconds);
}

// An observer whose helpers work from t* = 1 to t* = 2 (a movie's batch): the physics leaves
// them a core meanwhile and takes it back after, and ends with the run's own thread count; the
// trajectory is bit for bit the one without the observer.
class CoreBorrower : public Observer {
 public:
  explicit CoreBorrower(const World& world) : world_(world) {}
  void observe(const World&, const RunState&, double t_star) override { working_ = t_star >= 1.0 && t_star < 2.0; }
  int helper_cores() override {
    // The step just taken was stepped with the threads this call's predecessor's answer left.
    (answered_ ? while_working : otherwise).insert(world_.settings().threads);
    answered_ = working_;
    return working_ ? 1 : 0;
  }
  std::set<int> while_working, otherwise;

 private:
  const World& world_;
  bool working_ = false, answered_ = false;
};

TEST(Run, HelpersWorkingGetACoreOfTheirOwn) {
  const int cores = available_cores();
  SceneDef s = pit_and_roller();
  s.output.end_time = 3.0;
  const SceneSetup setup = derive_setup(s);
  World plain = build_explicit_world(s, setup, cores);
  AvalancheRun(plain, s, setup).run();

  World w = build_explicit_world(s, setup, cores);
  CoreBorrower borrower(w);
  AvalancheRun run(w, s, setup);
  run.add_observer(borrower, {0.25, 0.0, {}});
  const RunResult r = run.run();
  EXPECT_EQ(borrower.while_working, std::set<int>{std::max(1, cores - 1)});
  EXPECT_EQ(borrower.otherwise, std::set<int>{cores});
  EXPECT_EQ(w.settings().threads, cores);
  EXPECT_EQ(r.fewest_threads, cores);  // lending a core is not a governor's drop
  ASSERT_EQ(w.particles().size(), plain.particles().size());
  for (std::size_t i = 0; i < w.particles().size(); ++i) {
    EXPECT_EQ(w.particles().x[i], plain.particles().x[i]);
    EXPECT_EQ(w.particles().omega[i], plain.particles().omega[i]);
  }
}

// A wait for the pictures' helpers runs on every physics thread, each its own OpenMP thread.
TEST(Run, WaitingRunsOnEveryPhysicsThread) {
  for (int threads : {1, 2, 3}) {
    std::mutex m;
    std::set<int> seen;
    std::atomic<int> calls{0};
    wait_on_every_thread(threads, [&] {
      ++calls;
      std::lock_guard lock(m);
      seen.insert(omp_get_thread_num());
    });
    EXPECT_EQ(calls.load(), threads);
    EXPECT_EQ(static_cast<int>(seen.size()), threads);
  }
}

// Exact resume (SPEC §5, docs/reliability.md): a run killed right after any checkpoint and
// resumed gives every summary field, every time-series row and the final state of the run
// that never stopped. Cadences put checkpoints on sample times (0.5), on rest-test steps (a
// multiple of the rest test's step cadence) and between both (0.37).
class CheckpointTaker : public Observer {
 public:
  void observe(const World& world, const RunState& state, double t_star) override {
    if (t_star > 0 && taken.size() < 3) taken.push_back(encode_checkpoint(world, 1, encode_run_state(state)));
  }
  std::vector<std::string> taken;
};

nlohmann::json summary_without_wall_times(const RunResult& r, const SceneSetup& setup) {
  io::SummaryContext ctx;
  ctx.unit_length = setup.unit_length;
  ctx.unit_time = setup.unit_time;
  nlohmann::json j = nlohmann::json::parse(io::summary_json(r, ctx));
  for (const char* k : {"wall_seconds", "particle_steps_per_second", "profile_seconds", "threads_fewest"}) j.erase(k);
  return j;
}

TEST(Run, ResumeFromAnyCheckpointIsTheUninterruptedRun) {
  SceneDef s = testing::small_pile();
  s.rest.ek_threshold = 1e-3;
  s.rest.hold = 1.0;
  s.rest.max_time = 30.0;
  s.output.timeseries_every = 0.5;
  const SceneSetup setup = derive_setup(s);
  World released = build_settled_pile(s, setup, 1);
  release(released, setup);
  const auto steps_per_unit = static_cast<std::int64_t>(std::ceil(setup.unit_time / setup.dt));
  const double rest_test_every = 7.0 * std::max<std::int64_t>(1, steps_per_unit / 20) * setup.dt / setup.unit_time;

  for (double every : {0.5, rest_test_every, 0.37}) {
    World w = released;
    AvalancheRun straight(w, s, setup);
    CheckpointTaker taker;
    straight.add_observer(taker, {every, every, {}});
    Recorder snapshots;  // an observer at fixed times: none is repeated or lost by a resume
    straight.add_observer(snapshots, {0.0, 0.0, {0.0, 1.0, 2.2, 5.0}});
    const RunResult whole = straight.run();
    ASSERT_TRUE(whole.at_rest);
    ASSERT_EQ(taker.taken.size(), 3u);
    for (const std::string& bytes : taker.taken) {
      // Once with another thread count: the ledger's sums too are the same bits.
      World again = build_explicit_world(s, setup, &bytes == &taker.taken[0] ? 2 : 1);
      const RunState state = decode_run_state(decode_checkpoint(bytes, 1, again, "ckpt"), "ckpt");
      const double t_resume = again.time() / setup.unit_time;
      AvalancheRun resumed(again, s, setup, state);
      Recorder later;
      resumed.add_observer(later, {0.0, 0.0, {0.0, 1.0, 2.2, 5.0}});
      const RunResult r = resumed.run();
      SCOPED_TRACE("cadence " + std::to_string(every) + ", resumed at t* = " + std::to_string(t_resume));
      EXPECT_EQ(summary_without_wall_times(r, setup), summary_without_wall_times(whole, setup));
      const auto& a = resumed.state().series;
      const auto& b = straight.state().series;
      ASSERT_EQ(a.size(), b.size());
      EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(TimeseriesRow)), 0);
      EXPECT_EQ(again.particles().x, w.particles().x);
      EXPECT_EQ(again.particles().omega, w.particles().omega);
      std::vector<double> missed;  // what the resumed run drew is what the whole run drew after t_resume
      for (double t : snapshots.times) if (t > t_resume + 1e-9) missed.push_back(t);
      EXPECT_EQ(later.times, missed);
    }
  }
}

// A run resumed from its final checkpoint (after rest, or after output.end_time) ends where it
// was, and adds no row; resumed with a later end time it is the run that never stopped there.
TEST(Run, ResumingAnEndedRunAddsNothing) {
  SceneDef s = pit_and_roller();
  s.output.end_time = 3.0;
  const SceneSetup setup = derive_setup(s);
  World w = build_explicit_world(s, setup, 1);
  AvalancheRun first(w, s, setup);
  const RunResult r1 = first.run();
  ASSERT_TRUE(r1.reached_end_time);
  EXPECT_NEAR(r1.t_star_end, 3.0, 0.5 * setup.dt / setup.unit_time + 1e-12);  // to the step
  const std::string bytes = encode_checkpoint(w, 1, encode_run_state(first.state()));

  World again = build_explicit_world(s, setup, 1);
  AvalancheRun same(again, s, setup, decode_run_state(decode_checkpoint(bytes, 1, again, "c"), "c"));
  const RunResult r2 = same.run();
  EXPECT_EQ(summary_without_wall_times(r2, setup), summary_without_wall_times(r1, setup));
  EXPECT_EQ(same.state().series.size(), first.state().series.size());

  SceneDef longer = s;
  longer.output.end_time = 6.0;
  World straight_world = build_explicit_world(s, setup, 1);
  AvalancheRun straight(straight_world, longer, setup);
  const RunResult whole = straight.run();
  World cont = build_explicit_world(s, setup, 1);
  AvalancheRun continued(cont, longer, setup, decode_run_state(decode_checkpoint(bytes, 1, cont, "c"), "c"));
  const RunResult r3 = continued.run();
  EXPECT_EQ(summary_without_wall_times(r3, setup), summary_without_wall_times(whole, setup));
  const auto& a = continued.state().series;
  const auto& b = straight.state().series;
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(TimeseriesRow)), 0);
}

}  // namespace
}  // namespace runout

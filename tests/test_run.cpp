// The run loop: the at-rest criterion and observer scheduling.
#include <gtest/gtest.h>

#include <cmath>

#include "runout/errors.hpp"
#include "runout/run.hpp"
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
  AvalancheRun resumed_bare(w, bare, setup, saved);  // the same selection resumes
}

class Recorder : public Observer {
 public:
  void observe(const World&, double t_star) override { times.push_back(t_star); }
  std::vector<double> times;
};

TEST(Run, ObserversFireOnTheNearestStep) {
  SceneDef s = floor_scene();
  s.particles = {testing::disc(0.0, 0.3, 0.5)};
  s.output.end_time = 3.0;
  const SceneSetup setup = derive_setup(s);
  World w = build_explicit_world(s, setup, 1);
  AvalancheRun run(w, s, setup);
  Recorder every, at;
  run.add_observer(every, {1.0, 0.0, {}});
  run.add_observer(at, {0.0, 0.0, {0.25, 2.5}});
  const RunResult r = run.run();
  EXPECT_TRUE(r.reached_end_time);  // even if t* ends up to half a step before 3
  const double half_step = 0.5 * setup.dt / setup.unit_time;
  ASSERT_EQ(every.times.size(), 4u);  // 0, 1, 2, 3
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(every.times[k], k, half_step + 1e-12);
  ASSERT_EQ(at.times.size(), 2u);
  EXPECT_NEAR(at.times[0], 0.25, half_step + 1e-12);
  EXPECT_NEAR(at.times[1], 2.5, half_step + 1e-12);
}

}  // namespace
}  // namespace runout

// Numerical stability at the extremes (SPEC §8): each case ends in a correct result or a clear
// error that names the cause and the knob to change; never NaN, a hang or silent garbage.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "runout/errors.hpp"
#include "runout/run.hpp"
#include "runout/setup.hpp"
#include "test_helpers.hpp"

namespace runout {
namespace {

// Head-on collision of two equal discs at closing speed 2 v, no gravity. Returns e.
double restitution(double e_n, double v, double dt_fraction = 0.02) {
  SceneDef s = testing::two_species_scene(1.0, 1.0);
  s.material.restitution = e_n;
  s.integration.dt_fraction = dt_fraction;
  s.particles = {testing::disc(0.0, 0.0, 1.0, 0, v, 0.0), testing::disc(1.001, 0.0, 1.0, 1, -v, 0.0)};
  World w = testing::zero_gravity_world(s);
  testing::step_through_one_contact(w, [](const World& v) { return v.pairs().size() > 0 && v.pairs().fx[0] != 0.0; });
  return (w.particles().vx[1] - w.particles().vx[0]) / (2 * v);
}

// The design impact speed of this pair (SPEC §3): alphadot0 sqrt(g r*).
double design_speed() { return 10.0 * std::sqrt(9.81 * 0.25); }

TEST(Extremes, RestitutionNearZeroAndOne) {
  EXPECT_NEAR(restitution(0.01, 1.0), 0.01, 2e-3);
  EXPECT_NEAR(restitution(1.0, 1.0), 1.0, 2e-3);
}

TEST(Extremes, TenTimesTheDesignSpeedStillGivesEn) {
  // Walton–Braun is linear: the overlap grows with the speed but the restitution does not
  // change. At 10x the design speed the overlap is ~45 % of a radius: within the guard.
  EXPECT_NEAR(restitution(0.2, 0.5 * 10 * design_speed()), 0.2, 2e-3);
}

TEST(Extremes, ImpactFarBeyondTheDesignStopsWithAdvice) {
  try {
    restitution(0.2, 0.5 * 40 * design_speed());
    FAIL() << "an impact at 40x the design speed passed silently";
  } catch (const NumericalError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("overlap"), std::string::npos) << what;
    EXPECT_NE(what.find("contact.design_impact_speed"), std::string::npos) << what;
    EXPECT_NE(what.find("t* ="), std::string::npos) << what;
  }
}

TEST(Extremes, StepBeyondTheStabilityLimitIsRefused) {
  SceneDef s = testing::two_species_scene(1.0, 1.0);
  s.integration.dt_fraction = 0.5;
  try {
    derive_setup(s, "fast.toml");
    FAIL() << "dt_fraction 0.5 accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("integration.dt_fraction"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("stability"), std::string::npos) << e.what();
  }
  // Just inside the limit the step is coarse but stable: ~1.5 rad of the pair's oscillation
  // per step. The collision still returns within 30 % of e_n (0.249 measured), and a step
  // four times smaller at least halves the error (the integrator converges).
  const double coarse = restitution(0.2, 1.0, 0.3), finer = restitution(0.2, 1.0, 0.075);
  EXPECT_NEAR(coarse, 0.2, 0.06);
  EXPECT_LT(std::abs(finer - 0.2), 0.5 * std::abs(coarse - 0.2));
}

// A disc on a 30 degree incline with the given friction: its acceleration along the slope.
double slope_acceleration(double mu) {
  const double theta = kPi / 6;
  SceneDef s;
  s.species = {{"disc", 0.5, 0.0, 0.0}};
  s.material.friction = s.material.wall_friction = mu;
  s.walls = {{"slope", {{-100 * std::cos(theta), 100 * std::sin(theta)}, {100 * std::cos(theta), -100 * std::sin(theta)}}, true}};
  s.particles = {testing::disc(0.2499 * std::sin(theta), 0.2499 * std::cos(theta), 0.5)};
  const SceneSetup setup = derive_setup(s);
  World w = build_explicit_world(s, setup, 1);
  auto along = [&] { return w.particles().vx[0] * std::cos(theta) - w.particles().vy[0] * std::sin(theta); };
  while (w.time() < 0.2) w.step();
  const double t1 = w.time(), v1 = along();
  while (w.time() < 1.0) w.step();
  return (along() - v1) / (w.time() - t1);
}

TEST(Extremes, FrictionZeroSlidesAndFrictionTenRolls) {
  EXPECT_NEAR(slope_acceleration(0.0), 9.81 * 0.5, 0.005 * 9.81);               // g sin
  EXPECT_NEAR(slope_acceleration(10.0), 5.0 / 7.0 * 9.81 * 0.5, 0.005 * 9.81);  // 5/7 g sin
}

// mu = 0 everywhere: no tangential spring is kept (the lists hold none), nothing can exert a
// torque, so no disc ever spins, and the ledger books no sliding loss.
TEST(Extremes, FrictionlessPileKeepsNoTangentialHistory) {
  SceneDef s = testing::small_pile();
  s.material.friction = s.material.wall_friction = 0.0;
  s.output.end_time = 3.0;
  const SceneSetup setup = derive_setup(s);
  World w = build_settled_pile(s, setup, 1);
  release(w, setup);
  EXPECT_FALSE(w.frictional());
  AvalancheRun run(w, s, setup);
  const RunResult r = run.run();
  EXPECT_GT(w.pairs().size(), 0u);
  EXPECT_GT(w.wall_contacts().size(), 0u);
  // Only Walton–Braun's overlap_max: no tangential spring is kept.
  EXPECT_EQ(w.history_width(), 1);
  EXPECT_EQ(w.pairs().history.size(), w.pairs().size());
  for (std::size_t k = 0; k < w.particles().size(); ++k) ASSERT_EQ(w.particles().omega[k], 0.0) << "disc " << k;
  EXPECT_EQ(w.dissipation().friction, 0.0);
  EXPECT_GT(r.com_rest.x(), r.com_release.x());  // it flowed
  // The same pile with friction keeps one spring per listed contact.
  SceneDef rough = testing::small_pile();
  World wr = build_settled_pile(rough, derive_setup(rough), 1);
  EXPECT_TRUE(wr.frictional());
  EXPECT_EQ(wr.history_width(), 2);
  EXPECT_EQ(wr.pairs().history.size(), 2 * wr.pairs().size());
}

TEST(Extremes, SizeRatioTwentyPileSettlesAndFlows) {
  SceneDef s;
  s.species = {{"large", 1.0, 0.1, 0.5}, {"small", 0.05, 0.1, 0.5}};
  s.avalanche = testing::short_avalanche(5.0, 3.0, 10.0, 10.0, 4);  // 2 large and 800 small discs
  s.preparation.settle_ek_threshold = 1e-5;
  s.preparation.settle_max_time = 250.0;
  s.output.end_time = 3.0;
  const SceneSetup setup = derive_setup(s);
  EXPECT_EQ(setup.counts[1], 800);
  // It settles and flows: the pile is at rest under the undamped law at release, every disc
  // stays inside the walls, and the mass moves down-slope.
  SettleReport report;
  World w = build_settled_pile(s, setup, 1, {}, &report);
  EXPECT_LT(report.ek_over_ep_undamped, s.preparation.settle_ek_threshold);
  release(w, setup);
  AvalancheRun run(w, s, setup);
  const RunResult r = run.run();
  EXPECT_NEAR(r.t_star_end, 3.0, 0.06);  // end_time is checked every 1/20 t* (run.cpp)
  ASSERT_EQ(w.particles().size(), 802u);
  w.check_escape(0.0);  // throws if a disc left the walls' box
  // Down-slope by more than a small disc's diameter in 3 t*.
  EXPECT_GT(r.com_rest.x() - r.com_release.x(), 0.05);
}

TEST(Extremes, DiscExactlyInTheInclineFloorCorner) {
  // Centre on the bisector of the 150 degree corner, touching both planes. Gravity presses it
  // into the floor, which presses it into the incline, whose push (up and to the right) rolls
  // it gently off the corner: a finite, slow, physical result, no launch from the shared vertex.
  const double theta = kPi / 6, r = 0.25;
  SceneDef s;
  s.species = {{"disc", 2 * r, 0.0, 0.0}};
  s.walls = {{"bed", {{-20 * std::cos(theta), 20 * std::sin(theta)}, {0.0, 0.0}, {20.0, 0.0}}, true}};
  s.particles = {testing::disc(r * std::tan(kPi / 12), r, 2 * r)};
  s.output.end_time = 20.0;
  const SceneSetup setup = derive_setup(s);
  World w = build_explicit_world(s, setup, 1);
  AvalancheRun run(w, s, setup);
  run.run();
  const auto& p = w.particles();
  EXPECT_GE(p.x[0], r * std::tan(kPi / 12) - 1e-6);  // off the corner, never into the incline
  EXPECT_LT(p.x[0], 1.0);
  EXPECT_NEAR(p.y[0], r, 0.01 * r);                  // resting on the floor
  EXPECT_LT(std::hypot(p.vx[0], p.vy[0]), 0.05);     // slow: no spurious kick
}

TEST(Extremes, OneDiscBouncesWithEnAndStaysOnTheFloor) {
  // Dropped from 2 m: each rebound leaves with e_n of the impact speed, so the first apex is
  // e_n^2 of the drop above the point where the disc leaves the floor. (Walton–Braun's unloading line is undamped, so
  // a lone disc keeps a tiny vertical ringing in its contact; it never leaves the floor.)
  SceneDef s;
  s.species = {{"disc", 0.5, 0.0, 0.0}};
  s.walls = {{"floor", {{-5.0, 0.0}, {5.0, 0.0}}, true}};
  s.particles = {testing::disc(0.0, 2.0, 0.5)};
  s.integration.dt_fraction = 0.01;  // the closed form is for the continuous contact
  const SceneSetup setup = derive_setup(s);
  check_runnable(s, setup, "one.toml");
  World w = build_explicit_world(s, setup, 1);
  bool bounced = false;
  double apex = 0;
  while (w.time() < 3.0) {
    w.step();
    const double vy = w.particles().vy[0];
    if (w.particles().y[0] < 0.25) bounced = true;
    if (bounced && vy > 0) apex = std::max(apex, w.particles().y[0]);
    if (bounced && vy < 0 && apex > 0.3) break;
  }
  // The disc leaves the floor from its dented height: Walton–Braun's unloading line ends at
  // overlap_0 = (1 - e^2) overlap_max, overlap_max = v sqrt(m / k_L) (SPEC §2).
  const double v = std::sqrt(2 * 9.81 * 1.75);
  const double overlap_max = v * std::sqrt(w.particles().mass[0] / setup.table.wall[0].k_load);
  const double leave = 0.25 - (1 - 0.04) * overlap_max;
  EXPECT_NEAR(apex - leave, 0.04 * 1.75, 0.02 * 0.04 * 1.75);
  while (w.time() < 10.0) w.step();
  EXPECT_NEAR(w.particles().y[0], 0.25, 0.01);
}

TEST(Extremes, EmptySceneIsAClearError) {
  SceneDef s;
  s.species = {{"disc", 0.5, 0.0, 0.0}};
  s.walls = {{"floor", {{-5.0, 0.0}, {5.0, 0.0}}, true}};
  const SceneSetup setup = derive_setup(s);
  try {
    check_runnable(s, setup, "empty.toml");
    FAIL() << "an empty scene was accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("empty.toml: particles"), std::string::npos) << e.what();
  }
}

TEST(Extremes, NonFiniteStateNamesStepTimeAndDisc) {
  SceneDef s;
  s.species = {{"disc", 0.5, 0.0, 0.0}};
  s.particles = {testing::disc(0.0, 0.0, 0.5), testing::disc(3.0, 0.0, 0.5, 0, std::nan(""), 0.0)};
  const SceneSetup setup = derive_setup(s);
  World w = build_explicit_world(s, setup, 1);
  try {
    for (int k = 0; k < 10; ++k) w.step();
    FAIL() << "NaN velocity went unnoticed";
  } catch (const NumericalError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("step 1 "), std::string::npos) << what;
    EXPECT_NE(what.find("disc id 2"), std::string::npos) << what;
    EXPECT_NE(what.find("integration.dt_fraction"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace runout

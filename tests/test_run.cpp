// The run loop: the at-rest criterion and observer scheduling.
#include <gtest/gtest.h>

#include <cmath>

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
  run.run();
  const double half_step = 0.5 * setup.dt / setup.unit_time;
  ASSERT_EQ(every.times.size(), 4u);  // 0, 1, 2, 3
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(every.times[k], k, half_step + 1e-12);
  ASSERT_EQ(at.times.size(), 2u);
  EXPECT_NEAR(at.times[0], 0.25, half_step + 1e-12);
  EXPECT_NEAR(at.times[1], 2.5, half_step + 1e-12);
}

}  // namespace
}  // namespace runout

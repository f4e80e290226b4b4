// One disc (sphere inertia) on a 30 degree incline (SPEC §2): rolls without slip with
// a = 5/7 g sin(theta) when tan(theta) <= 3.5 mu, slips with a = g (sin - mu cos) otherwise.
// With rotation locked it slides; down the slope and onto the floor it stops where the work
// of friction mu m g dx (dx horizontal, on both planes) plus the corner's loss equals m g H.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "runout/setup.hpp"
#include "test_helpers.hpp"

namespace runout {
namespace {

constexpr double kTheta = 30.0 * kPi / 180.0;
constexpr double kG = 9.81;

// A long incline through the origin, descending to +x, and a disc resting on it at distance
// `s0` up-slope from the origin.
World disc_on_incline(double mu, double s0, bool lock_rotation, bool with_floor, double& radius) {
  SceneDef s;
  s.species = {{"disc", 0.5, 0.0, 0.0}};
  s.material.friction = s.material.wall_friction = mu;
  const double L = 200.0;
  WallDef incline{"bed", {{-L * std::cos(kTheta), L * std::sin(kTheta)}, {0.0, 0.0}}, true};
  if (with_floor) incline.points.push_back({L, 0.0});
  else incline.points.back() = {L * std::cos(kTheta), -L * std::sin(kTheta)};
  s.walls = {incline};
  radius = 0.25;
  // Centre one radius off the incline, sitting with the static overlap m g cos / k_L.
  const SceneSetup pre = derive_setup(s);
  const PairCoefficients& c = pre.table.wall[0];
  const double m = sphere_mass(radius, s.material.density);
  const double overlap = m * kG * std::cos(kTheta) / c.k_load;
  const double off = radius - overlap;
  // The centre lies on the incline's outward normal n = (sin, cos) through the contact point.
  s.particles = {testing::disc(-s0 * std::cos(kTheta) + off * std::sin(kTheta),
                               s0 * std::sin(kTheta) + off * std::cos(kTheta), 2 * radius)};
  const SceneSetup setup = derive_setup(s);
  World w = build_explicit_world(s, setup, 1);
  if (lock_rotation) {
    Particles p = w.particles();
    p.inv_inertia[0] = 0.0;  // infinite inertia: the disc cannot spin
    w = World(std::move(p), w.segments(), w.table(), w.settings());
  }
  return w;
}

// Speed along the slope at two times after the contact has settled: a = dv / dt.
double slope_acceleration(World& w) {
  const double dir_x = std::cos(kTheta), dir_y = -std::sin(kTheta);
  auto along = [&] { return w.particles().vx[0] * dir_x + w.particles().vy[0] * dir_y; };
  while (w.time() < 0.2) w.step();
  const double t1 = w.time(), v1 = along();
  while (w.time() < 1.2) w.step();
  return (along() - v1) / (w.time() - t1);
}

TEST(Incline, RollsWithoutSlipWhenFrictionSuffices) {
  const double mu = 0.5;  // tan 30 = 0.577 <= 3.5 mu
  double r;
  World w = disc_on_incline(mu, 20.0, false, false, r);
  const double a = slope_acceleration(w);
  EXPECT_NEAR(a, 5.0 / 7.0 * kG * std::sin(kTheta), 0.005 * kG);
  // Rolling without slip: v = -omega r (clockwise is negative while moving to +x).
  const auto& p = w.particles();
  const double v = p.vx[0] * std::cos(kTheta) - p.vy[0] * std::sin(kTheta);
  EXPECT_NEAR(p.omega[0] * r, -v, 1e-3 * std::abs(v));
}

TEST(Incline, SlipsWhenFrictionIsTooLow) {
  const double mu = 0.1;  // tan 30 > 3.5 mu = 0.35
  double r;
  World w = disc_on_incline(mu, 20.0, false, false, r);
  EXPECT_NEAR(slope_acceleration(w), kG * (std::sin(kTheta) - mu * std::cos(kTheta)), 0.005 * kG);
}

TEST(Incline, LockedDiscSlidesAtCoulombRate) {
  const double mu = 0.3;
  double r;
  World w = disc_on_incline(mu, 20.0, true, false, r);
  EXPECT_NEAR(slope_acceleration(w), kG * (std::sin(kTheta) - mu * std::cos(kTheta)), 0.005 * kG);
}

TEST(Incline, LockedDiscStopsWhereFrictionWorkEqualsDrop) {
  // Block on slope then floor (thesis fig. 3.5): with friction work mu m g dx on each plane,
  // H / L = mu exactly if the corner cost nothing. A sharp corner costs more: landing on the
  // floor, the normal impulse m v sin(theta) brings friction mu m v sin(theta), so the floor
  // starts at u = v (cos - mu sin). Closed form: L = s cos + u^2 / (2 mu g), H = s sin.
  const double mu = 0.45, s0 = 12.0;
  double r;
  World w = disc_on_incline(mu, s0, true, true, r);
  const double x0 = w.particles().x[0], y0 = w.particles().y[0];
  while (w.time() < 0.5 || std::hypot(w.particles().vx[0], w.particles().vy[0]) > 1e-4) {
    w.step();
    ASSERT_LT(w.time(), 60.0);
  }
  const double H = y0 - w.particles().y[0], L = w.particles().x[0] - x0;
  const double s = H / std::sin(kTheta);  // slope length run by the centre
  const double v2 = 2 * kG * s * (std::sin(kTheta) - mu * std::cos(kTheta));
  const double u = std::sqrt(v2) * (std::cos(kTheta) - mu * std::sin(kTheta));
  const double L_expected = s * std::cos(kTheta) + u * u / (2 * mu * kG);
  EXPECT_NEAR(L, L_expected, 0.02 * L_expected);
  EXPECT_GT(H / L, mu);  // never more mobile than the block analysis allows
  EXPECT_NEAR(H / L, H / L_expected, 0.02 * mu);
}

}  // namespace
}  // namespace runout

// Rolling resistance (contact/rolling_sds.hpp) against the closed forms of a disc with sphere
// inertia (I = 2/5 m r^2) that rolls without slipping under a resisting torque of at most
// mu_r r N:
//  - on an incline of angle theta it is held when tan(theta) <= mu_r (the torque needed to hold
//    it, r m g sin(theta), is then within the limit r mu_r m g cos(theta)), and otherwise rolls
//    down at a = 5/7 g (sin(theta) - mu_r cos(theta));
//  - rolling on a floor at v0 it decelerates at 5/7 mu_r g and stops after 7 v0^2 / (10 mu_r g);
//  - what it loses is booked in the ledger: kinetic + potential + elastic + dissipated stays
//    the energy it started with.
#include <gtest/gtest.h>

#include <cmath>

#include "runout/setup.hpp"
#include "test_helpers.hpp"

namespace runout {
namespace {

constexpr double kG = 9.81, kR = 0.25, kMu = 1.0;

// A disc resting on a plane through the origin at angle theta (descending to +x), its centre
// one radius off the plane less the static overlap, moving down-slope at v0 and rolling.
World disc_on_plane(double theta, double mu_r, double v0) {
  SceneDef s;
  s.species = {{"disc", 2 * kR, 0.0, 0.0}};
  s.material.friction = s.material.wall_friction = kMu;
  s.contact.rolling_model = "sds";
  s.contact.rolling_friction = mu_r;
  const double L = 200.0;
  s.walls = {{"bed", {{-L * std::cos(theta), L * std::sin(theta)}, {L * std::cos(theta), -L * std::sin(theta)}}, true}};
  const SceneSetup pre = derive_setup(s);
  const double m = sphere_mass(kR, s.material.density);
  const double off = kR - m * kG * std::cos(theta) / pre.table.wall[0].k_load;
  const double dx = std::cos(theta), dy = -std::sin(theta);  // down the slope
  s.particles = {testing::disc(off * std::sin(theta), off * std::cos(theta), 2 * kR, 0, v0 * dx,
                               v0 * dy, -v0 / kR)};
  World w = build_explicit_world(s, derive_setup(s), 1);
  w.set_track_energy(true);
  return w;
}

double along_slope(const World& w, double theta) {
  return w.particles().vx[0] * std::cos(theta) - w.particles().vy[0] * std::sin(theta);
}

TEST(Rolling, HeldOnAnInclineExactlyWhenTanThetaIsWithinMuR) {
  const double theta = 30.0 * kPi / 180.0, t = std::tan(theta);
  for (double share : {0.97, 1.03}) {
    const double mu_r = share * t;
    World w = disc_on_plane(theta, mu_r, 0.0);
    while (w.time() < 0.5) w.step();
    const double t1 = w.time(), v1 = along_slope(w, theta);
    while (w.time() < 2.5) w.step();
    const double v = along_slope(w, theta);
    if (share > 1) {
      EXPECT_LT(std::abs(v), 1e-3) << "mu_r = " << mu_r << " holds it";
      EXPECT_LT(std::abs(v1), 1e-3) << "mu_r = " << mu_r << " holds it";
    } else {
      // Rolls, slowly, at 5/7 g (sin - mu_r cos) = 0.105 m/s^2; 0.03 of so small a difference
      // of two terms is 0.1 % of either.
      const double a = 5.0 / 7.0 * kG * (std::sin(theta) - mu_r * std::cos(theta));
      EXPECT_NEAR((v - v1) / (w.time() - t1), a, 0.03 * a) << "mu_r = " << mu_r << " rolls";
    }
  }
}

TEST(Rolling, RollsDownAtTheClosedFormAcceleration) {
  const double theta = 30.0 * kPi / 180.0, mu_r = 0.3;
  World w = disc_on_plane(theta, mu_r, 0.0);
  while (w.time() < 0.2) w.step();
  const double t1 = w.time(), v1 = along_slope(w, theta);
  while (w.time() < 1.2) w.step();
  const double a = (along_slope(w, theta) - v1) / (w.time() - t1);
  EXPECT_NEAR(a, 5.0 / 7.0 * kG * (std::sin(theta) - mu_r * std::cos(theta)), 0.005 * kG);
  // Still without slip, v = -omega r, up to the tangential spring's own (undamped) vibration.
  EXPECT_NEAR(w.particles().omega[0] * kR, -along_slope(w, theta), 5e-3 * along_slope(w, theta));
}

TEST(Rolling, StopsOnTheFloorAtTheClosedFormDistanceAndTheLedgerCloses) {
  const double mu_r = 0.1, v0 = 1.0;
  World w = disc_on_plane(0.0, mu_r, v0);
  const Particles& p = w.particles();
  const double x0 = p.x[0], y0 = p.y[0];
  const EnergyState e0 = w.energy(0.0);
  const double total0 = e0.translational + e0.rotational + e0.potential + e0.elastic;
  while (w.time() < 0.1 || std::abs(p.vx[0]) > 1e-4) {
    w.step();
    ASSERT_LT(w.time(), 10.0);
  }
  const double distance = p.x[0] - x0;
  const double expected = 7.0 * v0 * v0 / (10.0 * mu_r * kG);
  EXPECT_NEAR(distance, expected, 0.01 * expected);
  EXPECT_LT(std::abs(p.y[0] - y0), 1e-4 * kR);  // it rolled, it did not bounce
  const EnergyState e = w.energy(0.0);
  const Dissipation& lost = w.dissipation();
  const double total = e.translational + e.rotational + e.potential + e.elastic +
                       e.committed_normal + lost.normal + lost.friction + lost.rolling;
  const double kinetic0 = e0.translational + e0.rotational;
  EXPECT_NEAR(total, total0, 2e-3 * kinetic0);
  // Nearly all of the kinetic energy went into rolling resistance, none into sliding.
  EXPECT_NEAR(lost.rolling, kinetic0, 0.02 * kinetic0);
  EXPECT_LT(lost.friction, 1e-3 * kinetic0);
}

TEST(Rolling, NoRollingLawMeansNoTorqueBeyondFriction) {
  // mu_r = 0 with the law on: the limit is zero, the disc rolls on at constant speed.
  World w = disc_on_plane(0.0, 0.0, 1.0);
  while (w.time() < 1.0) w.step();
  EXPECT_NEAR(w.particles().vx[0], 1.0, 1e-3);
  EXPECT_EQ(w.dissipation().rolling, 0.0);
}

}  // namespace
}  // namespace runout

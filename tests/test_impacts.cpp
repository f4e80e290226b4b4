// Oblique impacts of a disc with sphere inertia on a wall, against the rigid-body closed form
// with Coulomb friction (e.g. Brach; Maw, Barber and Fawcett): when the contact slides
// throughout (|u_0| > 7/2 mu (1 + e_n) v_n, u_0 the contact point's tangential speed) the
// friction impulse is mu (1 + e_n) m v_n, so
//   v_t' = v_t - mu (1 + e_n) v_n,  omega' = omega_0 - 5/2 mu (1 + e_n) v_n / r,
// e_t = v_t' / v_t = 1 - mu (1 + e_n) / tan(theta), and tan(theta') = v_t' / (e_n v_n).
#include <gtest/gtest.h>

#include <cmath>

#include "runout/setup.hpp"
#include "test_helpers.hpp"

namespace runout {
namespace {

constexpr double kMu = 0.5, kE = 0.2, kR = 0.25;

struct Rebound {
  double vx, vy, omega;
};

// A disc approaching the floor with velocity (vx, -vn) and spin omega0; no gravity.
Rebound bounce(double vx, double vn, double omega0) {
  SceneDef s;
  s.species = {{"disc", 2 * kR, 0.0, 0.0}};
  s.material.wall_friction = kMu;
  s.material.wall_restitution = kE;
  s.integration.dt_fraction = 0.005;
  s.walls = {{"floor", {{-50.0, 0.0}, {50.0, 0.0}}, true}};
  s.particles = {testing::disc(0.0, kR + 1e-4, 2 * kR, 0, vx, -vn, omega0)};
  World w = testing::zero_gravity_world(s);
  testing::step_through_one_contact(
      w, [](const World& v) { return v.wall_contacts().size() > 0 && v.wall_contacts().fy[0] != 0.0; });
  return {w.particles().vx[0], w.particles().vy[0], w.particles().omega[0]};
}

class GrossSliding : public ::testing::TestWithParam<double> {};

TEST_P(GrossSliding, MatchesTheRigidBodyClosedForm) {
  const double theta = GetParam() * kPi / 180.0, v = 2.0;
  const double vt = v * std::sin(theta), vn = v * std::cos(theta);
  ASSERT_GT(std::tan(theta), 3.5 * kMu * (1 + kE)) << "not a gross-sliding case";
  const Rebound r = bounce(vt, vn, 0.0);
  const double e_t = 1 - kMu * (1 + kE) / std::tan(theta);
  EXPECT_NEAR(r.vy / vn, kE, 2e-3);
  EXPECT_NEAR(r.vx / vt, e_t, 5e-3);
  EXPECT_NEAR(r.omega, -2.5 * kMu * (1 + kE) * vn / kR, 0.01 * 2.5 * kMu * (1 + kE) * vn / kR);
  EXPECT_NEAR(std::atan2(r.vx, r.vy), std::atan2(e_t * vt, kE * vn), 5e-3);  // rebound angle
}

INSTANTIATE_TEST_SUITE_P(Incidence, GrossSliding, ::testing::Values(70.0, 75.0, 80.0, 85.0));

// Below the threshold the contact point stops slipping during the impact: the friction impulse
// is less than mu (1 + e_n) m v_n, so the disc keeps more tangential speed than the sliding
// formula gives, and never spins faster than rolling.
class Sticking : public ::testing::TestWithParam<double> {};

TEST_P(Sticking, FrictionImpulseStaysWithinCoulomb) {
  const double theta = GetParam() * kPi / 180.0, v = 2.0;
  const double vt = v * std::sin(theta), vn = v * std::cos(theta);
  ASSERT_LT(std::tan(theta), 3.5 * kMu * (1 + kE));
  const Rebound r = bounce(vt, vn, 0.0);
  EXPECT_NEAR(r.vy / vn, kE, 2e-3);
  const double friction_impulse = vt - r.vx;  // per unit mass
  EXPECT_LE(friction_impulse, kMu * (1 + kE) * vn * (1 + 1e-3));
  EXPECT_GE(r.vx, 0.0);
  // Angular impulse matches the tangential impulse (torque r F_t, I = 2/5 m r^2).
  EXPECT_NEAR(-r.omega * kR, 2.5 * friction_impulse, 1e-3 * vt);
}

INSTANTIATE_TEST_SUITE_P(Incidence, Sticking, ::testing::Values(5.0, 20.0, 35.0, 50.0, 60.0));

TEST(BackSpin, NormalImpactWithBackSpinSlidesThroughout) {
  // Straight down with back-spin: the contact point moves at u_0 = omega_0 r = -3 m/s (to -x),
  // > 7/2 mu (1 + e_n) v_n = 2.1 m/s, so it slides throughout: friction pushes the disc to +x.
  const double vn = 1.0, omega0 = -3.0 / kR;
  const Rebound r = bounce(0.0, vn, omega0);
  EXPECT_NEAR(r.vy, kE * vn, 2e-3);
  EXPECT_NEAR(r.vx, kMu * (1 + kE) * vn, 5e-3);
  EXPECT_NEAR(r.omega, omega0 + 2.5 * kMu * (1 + kE) * vn / kR, 0.01 * std::abs(omega0));
}

}  // namespace
}  // namespace runout

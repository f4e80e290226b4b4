// The Hertz–Mindlin law (contact/mindlin.hpp) on Chung & Ooi's (2011) benchmark test 4: an
// alumina sphere (here a disc with sphere mass and inertia, the same equations in the plane of
// impact) hits a rigid plane at 3.9 m/s at incident angles from 5 to 85 degrees. Below the
// gross-sliding angle (tan theta < 7/2 mu (1 + e_n), 32.6 degrees) the rebound depends on how
// the tangential spring stiffens and softens with the contact area; above it the contact slides
// throughout and the rigid-body closed form holds (test_impacts.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "runout/errors.hpp"
#include "runout/io/scene_file.hpp"
#include "runout/setup.hpp"
#include "test_helpers.hpp"

namespace runout {
namespace {

// Alumina (Chung & Ooi 2011, table 4): E = 380 GPa, nu = 0.23, rho = 4000 kg/m^3, R = 2.5 mm,
// mu = 0.092, e_n = 0.98; the plane is rigid.
constexpr double kE = 380e9, kNu = 0.23, kRho = 4000, kR = 2.5e-3, kMu = 0.092, kEn = 0.98;
constexpr double kSpeed = 3.9, kG = 9.81;

// Tangential coefficient of restitution v_t' / v_t of the centre, read off their figure
// (digitised points of the published alumina curve, as stored by Kratos' DEM benchmarks,
// tests/DEM3D_chung_ooi_tests/test4_data/paper_data/benchmark4_graph1_ref.dat).
struct Published {
  double angle_deg, e_t;
};
constexpr Published kBelowGrossSliding[] = {
    {5.168, 0.9481}, {10.158, 0.6870}, {14.990, 0.6244}, {20.059, 0.6161}, {25.050, 0.6343},
    {30.119, 0.6837}};

SceneDef alumina_on_a_plane(double angle_deg) {
  SceneDef s;
  s.species = {{"alumina", 2 * kR, 0.0, 0.0}};
  s.material.density = kRho;
  s.material.wall_friction = kMu;
  s.material.wall_restitution = kEn;
  s.contact.normal_model = "hertz";
  s.contact.tangential_model = "mindlin";
  // k_t / (dF_n / d overlap) = 8 G* a / (2 E* a) = 2 (1 - nu) / (2 - nu) against a rigid plane.
  s.contact.stiffness_ratio = 2 * (1 - kNu) / (2 - kNu);
  // Hertz's k = 4/3 E* sqrt(R): runout designs k from an impact speed (here 3.9 m/s, in units
  // of sqrt(g R)) and the peak overlap it may reach; that overlap is Hertz's for this k.
  const double e_star = kE / (1 - kNu * kNu);
  const double k_hertz = 4.0 / 3.0 * e_star * std::sqrt(kR);
  const double mass = sphere_mass(kR, kRho);
  const DashpotDesign d = dashpot_design(kEn, true);
  s.contact.design_impact_speed = kSpeed / std::sqrt(kG * kR);
  s.contact.design_max_overlap = d.peak_overlap * std::pow(mass * kSpeed * kSpeed / k_hertz, 0.4) / kR;
  s.integration.gravity = kG;
  s.integration.dt_fraction = 0.002;
  s.walls = {{"plane", {{-1.0, 0.0}, {1.0, 0.0}}, true}};
  const double theta = angle_deg * kPi / 180.0;
  s.particles = {testing::disc(0.0, kR + 1e-7, 2 * kR, 0, kSpeed * std::sin(theta),
                               -kSpeed * std::cos(theta))};
  return s;
}

struct Rebound {
  double e_t, e_n, omega;
};

Rebound impact(double angle_deg) {
  World w = testing::zero_gravity_world(alumina_on_a_plane(angle_deg));
  testing::step_through_one_contact(
      w, [](const World& v) { return v.wall_contacts().size() > 0 && v.wall_contacts().fy[0] != 0.0; });
  const double theta = angle_deg * kPi / 180.0;
  return {w.particles().vx[0] / (kSpeed * std::sin(theta)),
          w.particles().vy[0] / (kSpeed * std::cos(theta)), w.particles().omega[0]};
}

TEST(Mindlin, StiffnessIsHertzTimesTheRatio) {
  const SceneDef s = alumina_on_a_plane(10);
  const SceneSetup setup = derive_setup(s);
  const PairCoefficients& c = setup.table.wall[0];
  EXPECT_NEAR(Hertz::stiffness(c), 4.0 / 3.0 * kE / (1 - kNu * kNu) * std::sqrt(kR),
              1e-9 * Hertz::stiffness(c));
  const Mindlin::Params p = Mindlin::params(c);
  // 8 G* sqrt(R), G* = G / (2 - nu) on a rigid plane, G = E / (2 (1 + nu)).
  EXPECT_NEAR(p.k_root, 8 * kE / (2 * (1 + kNu)) / (2 - kNu) * std::sqrt(kR), 1e-9 * p.k_root);
}

TEST(Mindlin, ChungOoiTest4BelowGrossSliding) {
  for (const Published& point : kBelowGrossSliding) {
    const Rebound r = impact(point.angle_deg);
    std::printf("theta %6.3f deg: e_t %.4f (published %.4f), e_n %.4f\n", point.angle_deg, r.e_t,
                point.e_t, r.e_n);
    EXPECT_NEAR(r.e_n, kEn, 2e-3) << point.angle_deg << " degrees";
    // Digitised points: 0.015 covers reading the figure (runout is within 0.009 of each).
    EXPECT_NEAR(r.e_t, point.e_t, 0.015) << point.angle_deg << " degrees";
  }
}

TEST(Mindlin, GrossSlidingMatchesTheRigidBodyClosedForm) {
  for (double angle : {40.0, 60.0, 80.0}) {
    const double theta = angle * kPi / 180.0;
    const Rebound r = impact(angle);
    EXPECT_NEAR(r.e_t, 1 - kMu * (1 + kEn) / std::tan(theta), 2e-3) << angle << " degrees";
    const double vn = kSpeed * std::cos(theta);
    EXPECT_NEAR(r.omega, -2.5 * kMu * (1 + kEn) * vn / kR, 0.005 * 2.5 * kMu * (1 + kEn) * vn / kR)
        << angle << " degrees";
  }
}

TEST(Mindlin, ForceFollowsTheContactArea) {
  const Mindlin::Params p{2.0, 0.5};
  ContactKinematics k;
  k.dt = 1.0;
  double u = 0, loss = 0;
  k.overlap = 0.04;
  k.slip = 1e-3;
  const double f1 = Mindlin::force(p, k, 100.0, &u, loss);  // k_t = 2 sqrt(0.04) = 0.4
  EXPECT_DOUBLE_EQ(f1, 0.4 * 1e-3);
  k.slip = 0;
  k.overlap = 0.01;  // a halves: k_t and the force halve, the displacement stays
  EXPECT_NEAR(Mindlin::force(p, k, 100.0, &u, loss), f1 / 2, 1e-18);
  EXPECT_DOUBLE_EQ(u, 1e-3);
  EXPECT_EQ(loss, 0.0);
  // Slides: the cap mu F_n / k_t = 50 / 0.2 = 250 m is passed; it loses 50 N times the
  // slip beyond it.
  k.slip = 300.0;
  EXPECT_DOUBLE_EQ(Mindlin::force(p, k, 100.0, &u, loss), 50.0);
  EXPECT_NEAR(loss, 50.0 * (1e-3 + 300.0 - 250.0), 1e-9);
}

TEST(Mindlin, NeedsTheHertzNormalLaw) {
  const std::string disc = "[species.a]\ndiameter = 0.01\narea_share = 1\n[avalanche]\n";
  const std::string hertz = disc + "[contact]\nnormal_model = \"hertz\"\ntangential_model = \"mindlin\"\n";
  EXPECT_EQ(io::read_scene(hertz, "s.toml").contact.tangential_model, "mindlin");
  try {
    io::read_scene(disc + "[contact]\ntangential_model = \"mindlin\"\n", "s.toml");
    FAIL() << "Mindlin with Walton–Braun was accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("needs contact.normal_model = \"hertz\""), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace runout

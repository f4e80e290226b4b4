// Measurements of SPEC §6 on configurations whose answers are known by construction.
#include <gtest/gtest.h>

#include <cmath>

#include "runout/derive.hpp"
#include "runout/measure.hpp"

namespace runout {
namespace {

const std::vector<Segment> kFloor = make_segments({{"floor", {{-100.0, 0.0}, {100.0, 0.0}}, true}});

void add(Particles& p, int species, double x, double y, double r, double omega = 0) {
  const double m = sphere_mass(r, 2500.0);
  p.add(static_cast<std::int64_t>(p.size()), species, x, y, r, m, sphere_inertia(m, r), 0, 0, omega);
}

TEST(Measure, CentreOfMassAndEnergies) {
  Particles p;
  add(p, 0, 0.0, 1.0, 0.5);
  add(p, 0, 2.0, 3.0, 0.5);
  p.vx[1] = 2.0;
  const Eigen::Vector2d c = centre_of_mass(p);
  EXPECT_DOUBLE_EQ(c.x(), 1.0);
  EXPECT_DOUBLE_EQ(c.y(), 2.0);
  EXPECT_DOUBLE_EQ(translational_energy(p), 0.5 * p.mass[1] * 4.0);
  EXPECT_DOUBLE_EQ(potential_energy(p, 9.81), p.mass[0] * 9.81 * 4.0);
}

TEST(Measure, HeightAboveAnInclinedBed) {
  const auto bed = make_segments({{"bed", {{-10.0, 10.0 * std::tan(0.5)}, {0.0, 0.0}, {10.0, 0.0}}, true}});
  // A point 2 m off the incline along its normal.
  const double a = 0.5;
  EXPECT_NEAR(height_above_bed(bed, {-5.0 + 2.0 * std::sin(a), 5.0 * std::tan(a) + 2.0 * std::cos(a)}), 2.0, 1e-12);
  EXPECT_NEAR(height_above_bed(bed, {5.0, 3.0}), 3.0, 1e-12);
}

// A deposit on the floor: one row of small discs (d = 0.25) touching side by side, a row of
// large discs (D = 1) on top. The layer holds pi (d/2)^2 per d of length, so
// H_layer = pi d / (4 C) = 1.122 d for C = 0.7 (eq. 4.9), in every window.
TEST(Measure, BasalLayerOfOneSmallRow) {
  Particles p;
  const double d = 0.25, D = 1.0;
  for (int k = 0; k < 160; ++k) add(p, 1, 0.125 + k * d, 0.5 * d, 0.5 * d);
  for (int k = 0; k < 40; ++k) add(p, 0, 0.5 + k * D, d + 0.5 * D, 0.5 * D);
  const BasalLayer layer = basal_layer(p, kFloor, {1, 0}, D, 0.7);
  int members = 0;
  for (char m : layer.member) members += m;
  EXPECT_GE(members, 150);  // all but the ends of the row
  for (double h : layer.thickness) EXPECT_NEAR(h / d, kPi / (4 * 0.7), 0.03);
  EXPECT_LT(layer.spread / d, 0.03);
}

// Small discs between large ones, all on the floor: no small disc is under a large one.
TEST(Measure, NoBasalLayerWhenSmallDiscsSitBetweenLargeOnes) {
  Particles p;
  for (int k = 0; k < 40; ++k) {
    add(p, 0, k * 1.25, 0.5, 0.5);
    add(p, 1, k * 1.25 + 0.625, 0.125, 0.125);
  }
  const BasalLayer layer = basal_layer(p, kFloor, {1, 0}, 1.0, 0.7);
  for (char m : layer.member) EXPECT_EQ(m, 0);
  EXPECT_DOUBLE_EQ(layer.mean_thickness, 0.0);
}

TEST(Measure, ScatteredDiscsAreNotPartOfTheDeposit) {
  Particles p;
  for (int k = 0; k < 30; ++k)
    for (int row = 0; row < 4; ++row) add(p, 0, 0.5 + k, 0.5 + row, 0.5);
  add(p, 0, 60.0, 0.5, 0.5);  // two lone discs far ahead
  add(p, 0, 75.0, 0.5, 0.5);
  const BasalLayer layer = basal_layer(p, kFloor, {0, 0}, 1.0, 0.7);
  EXPECT_NEAR(layer.deposit_end - layer.deposit_start, 30.0, 1.0);
}

TEST(Measure, BasalSpinAveragesSmallDiscsTouchingTheBed) {
  Particles p;
  add(p, 1, 0.0, 0.1249, 0.125, -2.0);  // touching, rolling forward
  add(p, 1, 1.0, 0.1249, 0.125, -4.0);  // touching
  add(p, 1, 2.0, 1.0, 0.125, 50.0);     // in the air: not basal
  add(p, 0, 3.0, 0.499, 0.5, 10.0);     // large: not counted when small ones exist
  const double unit_time = std::sqrt(0.25 / 9.81);
  EXPECT_NEAR(basal_spin(p, kFloor, {1, 0}, unit_time), -3.0 * unit_time, 1e-12);
}

}  // namespace
}  // namespace runout

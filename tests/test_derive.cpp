// Derived parameters against SPEC §3's check table and disc counts against table 3.1.
#include <gtest/gtest.h>

#include <cmath>

#include "runout/setup.hpp"

namespace runout {
namespace {

SceneDef thesis(double d_small, double share_small) {
  SceneDef s;
  s.species = {{"large", 1.0, 0.1, 1.0 - share_small}, {"small", d_small, 0.1, share_small}};
  s.avalanche = AvalancheDef{};
  return s;
}

struct Row {
  double d, k_over_m, dt;
};

TEST(DerivedParameters, MatchSpecTable) {
  // SPEC §3: rho = 2500, e_n = 0.2, alphadot0 = 10, alphamax = 0.01, kratio = 1.
  const Row rows[] = {{0.12, 1.062e8, 4.88e-5}, {0.25, 5.10e7, 7.05e-5},
                      {0.333, 3.82e7, 8.14e-5}, {0.5, 2.55e7, 9.96e-5}};
  for (const auto& row : rows) {
    const SceneSetup s = derive_setup(thesis(row.d, 0.5));
    const PairCoefficients& c = s.table.between(1, 1);  // small–small
    EXPECT_NEAR(c.k_unload / c.reduced_mass, row.k_over_m, 0.005 * row.k_over_m) << "d = " << row.d;
    EXPECT_NEAR(s.dt, row.dt, 0.005 * row.dt) << "d = " << row.d;
    EXPECT_NEAR(s.unit_time / s.dt, 2266.0, 1.0) << "d = " << row.d;
    EXPECT_DOUBLE_EQ(c.k_load, 0.04 * c.k_unload);           // k_L = e_n^2 k_U
    EXPECT_DOUBLE_EQ(c.k_tangential, c.k_load);   // k_s = kratio k_L
  }
}

TEST(DerivedParameters, PeakOverlapFactor) {
  EXPECT_NEAR(peak_overlap_factor(0.2), 0.56997, 1e-5);  // SPEC §3
  EXPECT_DOUBLE_EQ(peak_overlap_factor(1.0), 1.0);
  // Independent check: the damped oscillator x'' + 2 zeta x' + x = 0, x'(0) = 1 peaks at f.
  const double e = 0.5, ln = std::log(e), zeta = -ln / std::sqrt(kPi * kPi + ln * ln);
  double x = 0, v = 1, peak = 0;
  for (int n = 0; n < 2'000'000 && v > 0; ++n) {
    v += (-2 * zeta * v - x) * 1e-6;
    x += v * 1e-6;
    peak = std::max(peak, x);
  }
  EXPECT_NEAR(peak_overlap_factor(e), peak, 1e-5);
}

TEST(DerivedParameters, MixedPairsDoNotSetTheStep) {
  // The ring formula gives mixed pairs a longer period than small–small (SPEC §3 table holds
  // for every %A_p).
  const SceneSetup a = derive_setup(thesis(0.25, 0.1));
  const SceneSetup b = derive_setup(thesis(0.25, 0.9));
  EXPECT_DOUBLE_EQ(a.dt, b.dt);
}

TEST(DerivedParameters, AbsentSpeciesDoNotSetTheStep) {
  // %A_p = 0 has no small discs: the step is that of the large discs alone. tau scales as
  // sqrt(m / k) with k / m* proportional to 1 / r*, i.e. as sqrt(r): sqrt(8.33) = 2.89 longer.
  SceneDef only_large;
  only_large.species = {{"large", 1.0, 0.1, 1.0}};
  only_large.avalanche = AvalancheDef{};
  const SceneSetup mono = derive_setup(only_large);
  const SceneSetup zero_small = derive_setup(thesis(0.12, 0.0));
  EXPECT_DOUBLE_EQ(zero_small.dt, mono.dt);
  EXPECT_NEAR(zero_small.dt / derive_setup(thesis(0.12, 0.25)).dt, std::sqrt(1.0 / 0.12), 0.01);
}

struct CountRow {
  double pct, ratio;
  int large, small;
};

TEST(DiscCounts, MatchThesisTable31) {
  const CountRow rows[] = {
      {0, 8.33, 500, 0},    {10, 8.33, 450, 3473}, {25, 8.33, 375, 8681}, {50, 8.33, 250, 17362},
      {10, 4, 450, 800},    {40, 4, 300, 3200},    {100, 4, 0, 8000},     {10, 3, 450, 450},
      {60, 3, 200, 2700},   {100, 3, 0, 4500},     {10, 2, 450, 200},     {50, 2, 250, 1000},
      {90, 2, 50, 1800}};
  for (const auto& r : rows) {
    // D/d = 8.33 is d = 0.12 m with D = 1 m (thesis table after 3.1); the others are exact.
    const double d = r.ratio == 8.33 ? 0.12 : 1.0 / r.ratio;
    const SceneSetup s = derive_setup(thesis(d, r.pct / 100.0));
    EXPECT_EQ(s.counts[0], r.large) << r.ratio << " / " << r.pct;
    EXPECT_EQ(s.counts[1], r.small) << r.ratio << " / " << r.pct;
  }
}

}  // namespace
}  // namespace runout

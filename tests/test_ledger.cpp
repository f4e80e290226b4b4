// The energy ledger (SPEC §8): E_total(0) = kinetic + rotational + potential + elastic +
// dissipated (normal, friction) + residual, with the residual the integrator's error.
#include <gtest/gtest.h>

#include <cmath>

#include "runout/run.hpp"
#include "test_helpers.hpp"

namespace runout {
namespace {

// Head-on Walton–Braun collision: the normal loss is exactly (1 - e_n^2) of the kinetic energy
// of the relative motion (equal masses: half of the total).
TEST(Ledger, BinaryCollisionLosesOneMinusEnSquared) {
  SceneDef s = testing::two_species_scene(1.0, 1.0);
  s.integration.dt_fraction = 0.005;
  s.particles = {testing::disc(0.0, 0.0, 1.0, 0, 1.0, 0.0), testing::disc(1.001, 0.0, 1.0, 1, -1.0, 0.0)};
  World w = testing::zero_gravity_world(s, true);
  const double ke0 = w.energy(0).translational;
  for (int n = 0; n < 200000 && w.time() < 0.05; ++n) w.step();
  const EnergyState e = w.energy(0);
  const double lost = w.dissipation().normal + e.committed_normal;
  EXPECT_NEAR(lost, (1 - 0.04) * ke0, 2e-3 * ke0);
  EXPECT_NEAR(e.translational + e.elastic + lost, ke0, 2e-3 * ke0);
  EXPECT_EQ(w.dissipation().friction, 0.0);
}

// The same balance for the linear dashpot, whose loss is its damping work plus the spring
// energy the no-tension cut throws away.
TEST(Ledger, DashpotCollisionBalances) {
  SceneDef s = testing::two_species_scene(1.0, 1.0);
  s.contact.normal_model = "linear_dashpot";
  s.integration.dt_fraction = 0.002;
  s.particles = {testing::disc(0.0, 0.0, 1.0, 0, 1.0, 0.0), testing::disc(1.001, 0.0, 1.0, 1, -1.0, 0.0)};
  World w = testing::zero_gravity_world(s, true);
  const double ke0 = w.energy(0).translational;
  while (w.time() < 0.05) w.step();
  const EnergyState e = w.energy(0);
  EXPECT_NEAR(e.translational + e.elastic + w.dissipation().normal, ke0, 1e-2 * ke0);
  EXPECT_NEAR(w.dissipation().normal, (1 - 0.04) * ke0, 1e-2 * ke0);
}

SceneDef small_pile(double dt_fraction) {
  SceneDef s = testing::small_pile();
  s.integration.dt_fraction = dt_fraction;
  s.output.end_time = 30.0;
  return s;
}

RunResult run_pile(double dt_fraction, std::vector<double>* xs = nullptr, SeriesSelection series = {},
                   Dissipation* lost = nullptr) {
  SceneDef s = small_pile(dt_fraction);
  s.output.series = series;
  const SceneSetup setup = derive_setup(s);
  World w = build_settled_pile(s, setup, 1);
  release(w, setup);
  AvalancheRun run(w, s, setup);
  const RunResult r = run.run();
  if (xs) xs->assign(w.particles().x.begin(), w.particles().x.end());
  if (lost) *lost = w.dissipation();
  return r;
}

TEST(Ledger, ResidualIsSmallAndShrinksWithTheStep) {
  const RunResult coarse = run_pile(0.1), fine = run_pile(0.025);
  const auto& e = coarse.final_energy;
  // Everything is accounted for: the terms add up to E_total(0) within the residual.
  EXPECT_GT(e.dissipated_normal_over_ep0 + e.dissipated_friction_over_ep0, 0.3);
  EXPECT_LT(coarse.worst_energy_residual, 0.08);  // measured 5 % for the quick pile at tau/10
  // First order in dt: a step four times smaller at least halves it.
  EXPECT_LT(fine.worst_energy_residual, 0.5 * coarse.worst_energy_residual);
}

// No output asks for the ledger (output.series without "energy"): the pair pass keeps no
// dissipation counters, the summary says so (NaN, null in JSON), and the flow is the same.
TEST(Ledger, KeepingTheLedgerDoesNotChangeTheTrajectory) {
  std::vector<double> with, without;
  Dissipation lost_with, lost_without;
  const RunResult full = run_pile(0.1, &with, {}, &lost_with);
  const RunResult bare = run_pile(0.1, &without, {false, false, false, false, false}, &lost_without);
  ASSERT_EQ(with.size(), without.size());
  for (std::size_t k = 0; k < with.size(); ++k) ASSERT_EQ(with[k], without[k]) << "disc " << k;
  EXPECT_EQ(full.mu_global, bare.mu_global);
  EXPECT_GT(lost_with.normal, 0.0);
  EXPECT_EQ(lost_without.normal, 0.0);
  EXPECT_EQ(lost_without.friction, 0.0);
  EXPECT_TRUE(std::isnan(bare.worst_energy_residual));
  EXPECT_TRUE(std::isnan(bare.max_overlap));
  EXPECT_TRUE(std::isnan(bare.final_energy.small_mean_height));
  EXPECT_TRUE(std::isnan(bare.final_energy.basal_spin));
  EXPECT_TRUE(std::isfinite(full.final_energy.basal_spin));
}

}  // namespace
}  // namespace runout

// e_n = 1, mu = 0: nothing dissipates, so kinetic + potential + elastic energy must stay where
// it started (SPEC §2). A symplectic integrator keeps the error bounded, not drifting.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "runout/measure.hpp"
#include "runout/setup.hpp"
#include "test_helpers.hpp"

namespace runout {
namespace {

// Spring energy of every touching pair and wall contact; for e_n = 1 Walton–Braun is a linear
// spring k_L = k_U.
double elastic_energy(const World& w) {
  const auto& p = w.particles();
  double e = 0;
  for (std::size_t a = 0; a < p.size(); ++a) {
    for (std::size_t b = a + 1; b < p.size(); ++b) {
      const double overlap = p.radius[a] + p.radius[b] - std::hypot(p.x[b] - p.x[a], p.y[b] - p.y[a]);
      if (overlap > 0) e += 0.5 * w.table().between(p.species[a], p.species[b]).k_load * overlap * overlap;
    }
    for (const auto& s : w.segments()) {
      const double overlap = p.radius[a] - distance_to(s, {p.x[a], p.y[a]});
      if (overlap > 0) e += 0.5 * w.table().wall[p.species[a]].k_load * overlap * overlap;
    }
  }
  return e;
}

double total_energy(const World& w) {
  const double g = -w.settings().gravity.y();
  return translational_energy(w.particles()) + rotational_energy(w.particles()) +
         potential_energy(w.particles(), g) + elastic_energy(w);
}

class ElasticFrictionless : public ::testing::TestWithParam<IntegratorKind> {};

TEST_P(ElasticFrictionless, TotalEnergyStaysBounded) {
  SceneDef s;
  s.species = {{"a", 0.5, 0.0, 0.0}, {"b", 0.3, 0.0, 0.0}};
  s.material.restitution = s.material.wall_restitution = 1.0;
  s.material.friction = s.material.wall_friction = 0.0;
  s.integration.integrator = GetParam();
  s.walls = {{"box", {{0.0, 8.0}, {0.0, 0.0}, {8.0, 0.0}, {8.0, 8.0}}, true}};
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j)
      s.particles.push_back(testing::disc(0.8 + 1.2 * i, 0.8 + 1.2 * j, (i + j) % 2 ? 0.5 : 0.3,
                                          (i + j) % 2 ? 0 : 1, u(rng), u(rng)));
  const SceneSetup setup = derive_setup(s);
  World w = build_explicit_world(s, setup, 1);
  const double e0 = total_energy(w);
  const double scale = translational_energy(w.particles());  // what the collisions exchange
  // Largest excursion in the first and in the second half: bounded means it does not grow.
  double worst_first = 0, worst_second = 0;
  std::int64_t contact_steps = 0;
  const int steps = 300000;
  for (int n = 1; n <= steps; ++n) {
    w.step();
    for (double f : w.pairs().fx) contact_steps += f != 0.0;
    if (n % 100 == 0) {
      const double err = std::abs(total_energy(w) - e0) / scale;
      (n <= steps / 2 ? worst_first : worst_second) = std::max(n <= steps / 2 ? worst_first : worst_second, err);
    }
  }
  EXPECT_GT(contact_steps, 5000);  // about 150 collisions, not a quiet box
  std::printf("energy over %.2f s: worst excursion %.3e then %.3e, end %.3e (of the initial "
              "kinetic energy)\n", w.time(), worst_first, worst_second,
              std::abs(total_energy(w) - e0) / scale);
  // Symplectic Euler reports velocities half a step off the positions, so its instantaneous
  // energy wanders more than velocity Verlet's; neither may drift.
  const double bound = GetParam() == IntegratorKind::symplectic_euler ? 0.1 : 0.05;
  EXPECT_LT(worst_first, bound);
  EXPECT_LT(worst_second, bound);
  EXPECT_LT(std::abs(total_energy(w) - e0) / scale, bound / 2) << "energy at the end";
}

INSTANTIATE_TEST_SUITE_P(BothIntegrators, ElasticFrictionless,
                         ::testing::Values(IntegratorKind::symplectic_euler,
                                           IntegratorKind::velocity_verlet));

}  // namespace
}  // namespace runout

// A golden file of the contact kernel's output (contact_forces.cpp) for every law the registry
// holds: a small fixed configuration of discs of two sizes, overlapping each other and two
// walls (a floor and a 30-degree plate) with set velocities and spins, stepped four times so
// the history (Walton–Braun's overlap_max, the tangential springs, the rolling spring) is used.
// Each contact's force on i and torques are compared with tests/golden/contact_forces.txt to
// 1e-12 of the largest force of its model (the kernel is pure; -ffp-contract=off keeps the
// arithmetic the same on any x86-64 build). Regenerate on purpose, after a change of a law,
// with RUNOUT_UPDATE_GOLDENS=1 and say why in the commit.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>

#include "runout/setup.hpp"
#include "test_helpers.hpp"

namespace runout {
namespace {

struct Laws {
  const char* normal;
  const char* tangential;
  const char* rolling;
  double friction;
};

// Every normal law with Cundall–Strack, each with no friction too, Mindlin on Hertz, and the
// rolling law on the seed's laws and on Hertz–Mindlin.
constexpr Laws kModels[] = {
    {"walton_braun", "cundall_strack", "none", 0.5}, {"walton_braun", "cundall_strack", "none", 0.0},
    {"linear_dashpot", "cundall_strack", "none", 0.5}, {"linear_dashpot", "cundall_strack", "none", 0.0},
    {"hertz", "cundall_strack", "none", 0.5}, {"hertz", "cundall_strack", "none", 0.0},
    {"hertz", "mindlin", "none", 0.5}, {"walton_braun", "cundall_strack", "sds", 0.5},
    {"hertz", "mindlin", "sds", 0.5}};

std::string model_name(const Laws& l) {
  return std::string(l.normal) + "+" + l.tangential + "+" + l.rolling + (l.friction > 0 ? "" : "+mu0");
}

World configuration(const Laws& l) {
  SceneDef s = testing::two_species_scene(1.0, 0.5);
  s.material.friction = s.material.wall_friction = l.friction;
  s.contact.normal_model = l.normal;
  s.contact.tangential_model = l.tangential;
  s.contact.rolling_model = l.rolling;
  s.contact.rolling_friction = 0.2;
  s.contact.stiffness_ratio = 0.8;
  const double t = kPi / 6;
  s.walls = {{"floor", {{-3.0, 0.0}, {3.0, 0.0}}, true},
             {"plate", {{1.2, 0.0}, {1.2 + 2 * std::cos(t), 2 * std::sin(t)}}, false}};
  // Overlaps of about 0.2-2 % of a radius, loading and unloading, with spins.
  s.particles = {testing::disc(-1.0, 0.497, 1.0, 0, 0.3, -0.2, 1.5),
                 testing::disc(-0.252, 0.24, 0.5, 1, -0.1, 0.05, -2.0),
                 testing::disc(0.245, 0.249, 0.5, 1, 0.2, -0.3, 0.7),
                 testing::disc(-0.5, 1.222, 1.0, 0, -0.05, -0.4, 0.0),
                 testing::disc(1.6, 0.9, 0.5, 1, 0.4, -0.6, 3.0)};
  World w = build_explicit_world(s, derive_setup(s), 1);
  return w;
}

// One line per touching contact and step: model step kind a b fx fy torque_a torque_b.
std::string kernel_output() {
  std::ostringstream out;
  char line[512];
  for (const Laws& l : kModels) {
    World w = configuration(l);
    for (int step = 1; step <= 4; ++step) {
      w.step();
      const auto& c = w.pairs();
      for (std::size_t q = 0; q < c.size(); ++q) {
        if (c.fx[q] == 0.0 && c.fy[q] == 0.0) continue;
        std::snprintf(line, sizeof line, "%s %d pair %lld %lld %.17g %.17g %.17g %.17g\n",
                      model_name(l).c_str(), step, (long long)w.particles().id[c.i[q]],
                      (long long)w.particles().id[c.j[q]], c.fx[q], c.fy[q], c.torque[q], c.torque[c.j_offset() + q]);
        out << line;
      }
      const auto& wc = w.wall_contacts();
      for (std::size_t q = 0; q < wc.size(); ++q) {
        if (wc.fx[q] == 0.0 && wc.fy[q] == 0.0) continue;
        std::snprintf(line, sizeof line, "%s %d wall %lld %d %.17g %.17g %.17g 0\n",
                      model_name(l).c_str(), step, (long long)w.particles().id[wc.disc[q]],
                      wc.segment[q], wc.fx[q], wc.fy[q], wc.torque[q]);
        out << line;
      }
    }
  }
  return out.str();
}

struct Row {
  std::string key;
  double v[4];
};

std::vector<Row> parse(const std::string& text) {
  std::vector<Row> rows;
  std::istringstream in(text);
  std::string model, kind;
  int step;
  long long a, b;
  Row r;
  while (in >> model >> step >> kind >> a >> b >> r.v[0] >> r.v[1] >> r.v[2] >> r.v[3]) {
    r.key = model + " " + std::to_string(step) + " " + kind + " " + std::to_string(a) + " " + std::to_string(b);
    rows.push_back(r);
  }
  return rows;
}

TEST(GoldenForces, EveryLawMatchesTheStoredForcesAndTorques) {
  const std::string path = std::string(RUNOUT_SOURCE_DIR) + "/tests/golden/contact_forces.txt";
  const std::string now = kernel_output();
  if (const char* u = std::getenv("RUNOUT_UPDATE_GOLDENS"); u && std::string(u) == "1") {
    std::ofstream(path) << now;
    GTEST_SKIP() << "wrote " << path;
  }
  std::ifstream in(path);
  ASSERT_TRUE(in) << path << " is missing (RUNOUT_UPDATE_GOLDENS=1 writes it)";
  std::stringstream stored;
  stored << in.rdbuf();
  const auto want = parse(stored.str()), got = parse(now);
  ASSERT_EQ(got.size(), want.size()) << "a different set of touching contacts";
  // Every model has pair and wall contacts, friction torques where mu > 0, and its own numbers.
  std::map<std::string, double> largest;
  for (const Row& r : want) {
    const std::string model = r.key.substr(0, r.key.find(' '));
    largest[model] = std::max({largest[model], std::abs(r.v[0]), std::abs(r.v[1])});
  }
  EXPECT_EQ(largest.size(), std::size(kModels));
  for (std::size_t k = 0; k < want.size(); ++k) {
    ASSERT_EQ(got[k].key, want[k].key);
    const double scale = largest[want[k].key.substr(0, want[k].key.find(' '))];
    for (int m = 0; m < 4; ++m)
      EXPECT_NEAR(got[k].v[m], want[k].v[m], 1e-12 * scale) << want[k].key << " column " << m;
  }
}

}  // namespace
}  // namespace runout

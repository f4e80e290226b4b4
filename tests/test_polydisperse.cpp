// Polydisperse piles: a size distribution by area split into classes (size_distribution.hpp),
// against closed forms and numerical quadrature; the scene file's distribution tables; the
// measurements with more than two species.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numeric>

#include "runout/derive.hpp"
#include "runout/errors.hpp"
#include "runout/io/scene_file.hpp"
#include "runout/measure.hpp"
#include "runout/setup.hpp"
#include "runout/size_distribution.hpp"

namespace runout {
namespace {

// Composite Simpson on [a, b] in ln d (the densities below are smooth there).
double integrate(const std::function<double(double)>& f, double a, double b, int n = 20000) {
  const double la = std::log(a), lb = std::log(b), h = (lb - la) / n;
  double s = 0;
  for (int k = 0; k <= n; ++k) {
    const double d = std::exp(la + k * h);
    const double w = (k == 0 || k == n) ? 1 : (k % 2 ? 4 : 2);
    s += w * f(d) * d;  // dd = d dln d
  }
  return s * h / 3;
}

// The area density of a lognormal by area, without its truncation constant.
double lognormal_area_density(double d, double median, double sigma) {
  const double z = std::log(d / median) / sigma;
  return std::exp(-0.5 * z * z) / (d * sigma * std::sqrt(2 * kPi));
}

SpeciesDef lognormal(double lo, double hi, double median, double sigma) {
  SpeciesDef f;
  f.name = "grains";
  f.distribution = SizeDistribution::lognormal;
  f.min_diameter = lo;
  f.max_diameter = hi;
  f.median = median;
  f.sigma = sigma;
  f.area_share = 1.0;
  return f;
}

TEST(Polydisperse, ClassesTileTheRangeAndShareTheArea) {
  const SpeciesDef f = lognormal(0.1, 1.0, 0.35, 0.6);
  const auto classes = split_into_classes(f, 5);
  ASSERT_EQ(classes.size(), 5u);
  const double total = integrate([&](double d) { return lognormal_area_density(d, 0.35, 0.6); }, 0.1, 1.0);
  double share = 0;
  for (std::size_t k = 0; k < classes.size(); ++k) {
    const auto& c = classes[k];
    EXPECT_EQ(c.name, "grains_" + std::to_string(k + 1));
    EXPECT_NEAR(c.max_diameter / c.min_diameter, std::pow(10.0, 0.2), 1e-12);  // equal in ln d
    if (k > 0) EXPECT_DOUBLE_EQ(c.min_diameter, classes[k - 1].max_diameter);
    EXPECT_DOUBLE_EQ(c.diameter, std::sqrt(c.min_diameter * c.max_diameter));
    const double part = integrate([&](double d) { return lognormal_area_density(d, 0.35, 0.6); }, c.min_diameter,
                                  c.max_diameter);
    EXPECT_NEAR(c.area_share, part / total, 1e-9) << k;
    share += c.area_share;
  }
  EXPECT_NEAR(share, 1.0, 1e-12);
  EXPECT_DOUBLE_EQ(classes.front().min_diameter, 0.1);
  EXPECT_DOUBLE_EQ(classes.back().max_diameter, 1.0);

  // Uniform by area: each class's share is its width over the range's.
  SpeciesDef u = f;
  u.distribution = SizeDistribution::uniform;
  for (const auto& c : split_into_classes(u, 4))
    EXPECT_NEAR(c.area_share, (c.max_diameter - c.min_diameter) / 0.9, 1e-12);
}

TEST(Polydisperse, MeanInverseSquareAgainstQuadrature) {
  SpeciesDef u = lognormal(0.2, 0.5, 1, 1);
  u.distribution = SizeDistribution::uniform;
  EXPECT_NEAR(mean_inverse_square_diameter(u), integrate([](double d) { return 1 / (d * d); }, 0.2, 0.5) / 0.3, 1e-9);
  EXPECT_DOUBLE_EQ(mean_inverse_square_diameter(u), 1 / (0.2 * 0.5));
  for (const auto& [median, sigma] : std::vector<std::pair<double, double>>{{0.35, 0.6}, {0.05, 0.3}, {2.0, 1.5}}) {
    const SpeciesDef l = lognormal(0.1, 1.0, median, sigma);
    auto f = [&](double d) { return lognormal_area_density(d, median, sigma); };
    const double want = integrate([&](double d) { return f(d) / (d * d); }, 0.1, 1.0) / integrate(f, 0.1, 1.0);
    EXPECT_NEAR(mean_inverse_square_diameter(l) / want, 1.0, 1e-8) << median << " " << sigma;
  }
  SpeciesDef thesis;
  thesis.diameter = 0.25;  // the spread law keeps SPEC eq. 3.1's count
  EXPECT_DOUBLE_EQ(mean_inverse_square_diameter(thesis), 16.0);
}

// The drawn diameters are quantiles of the number distribution: their areas reproduce the
// class's area distribution, and their count fills its area.
TEST(Polydisperse, DrawnDiametersFollowTheAreaDistribution) {
  for (SizeDistribution law : {SizeDistribution::uniform, SizeDistribution::lognormal}) {
    SpeciesDef c = lognormal(0.1, 1.0, 0.35, 0.6);
    c.distribution = law;
    const int n = 4000;
    const auto d = class_diameters(c, n);
    ASSERT_EQ(d.size(), static_cast<std::size_t>(n));
    EXPECT_TRUE(std::is_sorted(d.begin(), d.end()));
    EXPECT_GT(d.front(), 0.1);
    EXPECT_LT(d.back(), 1.0);
    double area = 0, below = 0;
    for (double x : d) {
      area += x * x;
      if (x < 0.3) below += x * x;
    }
    // Mean disc area = (pi/4) / E[1/d^2] (count = area * 4/pi * E[1/d^2]).
    EXPECT_NEAR(area / n * mean_inverse_square_diameter(c), 1.0, 2e-3) << static_cast<int>(law);
    const double want = law == SizeDistribution::uniform
                            ? (0.3 - 0.1) / 0.9
                            : integrate([](double x) { return lognormal_area_density(x, 0.35, 0.6); }, 0.1, 0.3) /
                                  integrate([](double x) { return lognormal_area_density(x, 0.35, 0.6); }, 0.1, 1.0);
    EXPECT_NEAR(below / area, want, 2e-3) << static_cast<int>(law);
  }
}

const std::string kPoly = R"(
[species.grains]
distribution = "lognormal"
median = 0.4
sigma = 0.5
min = 0.15
max = 1.0
classes = 5
area_share = 1.0
[avalanche]
incline_length = 10.0
)";

TEST(Polydisperse, SceneFileSplitsAndReadsBack) {
  const SceneDef s = io::read_scene(kPoly, "poly.toml");
  ASSERT_EQ(s.species.size(), 5u);
  EXPECT_EQ(s.species[0].name, "grains_1");
  const std::string resolved = io::write_scene(s);
  const SceneDef back = io::read_scene(resolved, "resolved.toml");
  EXPECT_EQ(io::write_scene(back), resolved);
  ASSERT_EQ(back.species.size(), 5u);
  for (std::size_t k = 0; k < 5; ++k) {
    EXPECT_DOUBLE_EQ(back.species[k].diameter, s.species[k].diameter);
    EXPECT_DOUBLE_EQ(back.species[k].area_share, s.species[k].area_share);
  }
  // The setup: counts from each class's mean 1/d^2, d the smallest class's nominal diameter,
  // and a time step set by the smallest disc of the smallest class.
  const SceneSetup setup = derive_setup(s, "poly.toml");
  const double D = s.species[4].diameter;
  for (std::size_t k = 0; k < 5; ++k)
    EXPECT_EQ(setup.counts[k], (int)std::ceil(s.species[k].area_share * 500 * D * D *
                                         mean_inverse_square_diameter(s.species[k]) * (1 - 1e-9)));
  EXPECT_DOUBLE_EQ(setup.unit_length, s.species[0].diameter);
  EXPECT_EQ(setup.roles.small, 0);
  EXPECT_EQ(setup.roles.large, 4);
  SceneDef nominal = s;  // the same classes drawn at their nominal sizes only
  for (auto& sp : nominal.species) sp.distribution = SizeDistribution::spread;
  EXPECT_LT(setup.tau_min, derive_setup(nominal, "nominal").tau_min);
}

TEST(Polydisperse, BadDistributionsAreNamed) {
  auto expect = [](const std::string& body, const std::string& key, const std::string& what) {
    try {
      io::read_scene("[species.g]\n" + body + "\narea_share = 1.0\n[avalanche]\n", "bad.toml");
      FAIL() << body;
    } catch (const ConfigError& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find("bad.toml"), std::string::npos) << m;
      EXPECT_NE(m.find(key), std::string::npos) << m;
      EXPECT_NE(m.find(what), std::string::npos) << m;
    }
  };
  expect("distribution = \"lognormal\"\nmin = 0.5\nmax = 0.2\nmedian = 0.3\nsigma = 0.5", "species.g.max", "larger than min");
  expect("distribution = \"lognormal\"\nmin = 0.1\nmax = 0.2", "species.g.median", "required");
  expect("distribution = \"uniform\"\nmin = 0.1\nmax = 0.2\nsigma = 0.5", "species.g.sigma", "lognormal");
  expect("distribution = \"uniform\"\nmin = 0.1\nmax = 0.2\ndiameter = 0.5", "species.g.diameter", "unknown");
  expect("distribution = \"gamma\"\nmin = 0.1\nmax = 0.2", "species.g.distribution", "uniform");
  expect("distribution = \"uniform\"\nmin = 0.001\nmax = 0.2", "species.g.max", "100 times");
  expect("distribution = \"uniform\"\nmin = 0.1\nmax = 0.2\nclasses = 40", "species.g.classes", "[1, 16]");
  expect("distribution = \"lognormal\"\nmin = 0.1\nmax = 0.2\nmedian = 50.0\nsigma = 0.1", "species.g.median",
         "millionth");
}

// Three species: the basal layer is the smallest class below the contour drawn by every larger
// disc. A row of small discs on the floor (d = 0.2), medium discs (0.5) on them with small
// ones in their gaps, large discs (1.0) on top: only the bottom row is the layer.
TEST(Polydisperse, BasalLayerIsTheSmallestClassUnderEveryLargerDisc) {
  const auto floor = make_segments({{"floor", {{-100.0, 0.0}, {100.0, 0.0}}, true}});
  Particles p;
  auto add = [&](int species, double x, double y, double r) {
    const double m = sphere_mass(r, 2500.0);
    p.add(static_cast<std::int64_t>(p.size()), species, x, y, r, m, sphere_inertia(m, r), 0, 0, 0);
  };
  const int row = 150;
  for (int k = 0; k < row; ++k) add(0, 0.1 + 0.2 * k, 0.1, 0.1);                 // small, on the floor
  for (int k = 0; k < 30; ++k) {
    add(1, 0.25 + 1.0 * k, 0.2 + 0.25, 0.25);                                    // medium on the row
    add(0, 0.75 + 1.0 * k, 0.2 + 0.1, 0.1);                                      // small in the gaps
  }
  for (int k = 0; k < 30; ++k) add(2, 0.5 + 1.0 * k, 0.7 + 0.5, 0.5);            // large on top
  const BasalLayer layer = basal_layer(p, floor, {0, 2}, 1.0, 0.7);
  int bottom = 0, gaps = 0;
  for (std::size_t k = 0; k < p.size(); ++k) {
    if (!layer.member[k]) continue;
    EXPECT_EQ(p.species[k], 0);
    (p.y[k] < 0.15 ? bottom : gaps) += 1;
  }
  EXPECT_EQ(gaps, 0);  // above the medium discs' bottom edge (0.2): not the layer
  EXPECT_GE(bottom, row - 10);

  const auto h = mean_heights_by_species(p, floor, 4);
  EXPECT_NEAR(h[1], 0.45, 1e-12);
  EXPECT_NEAR(h[2], 1.2, 1e-12);
  EXPECT_TRUE(std::isnan(h[3]));
  EXPECT_NEAR(h[0], (row * 0.1 + 30 * 0.3) / (row + 30), 1e-12);
}

}  // namespace
}  // namespace runout

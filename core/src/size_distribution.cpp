#include "runout/size_distribution.hpp"

#include <cmath>
#include <string>

namespace runout {

namespace {

double normal_cdf(double z) { return 0.5 * std::erfc(-z / std::sqrt(2.0)); }

// Lognormal by area: z = ln(d / median) / sigma.
double z_of(const SpeciesDef& s, double d) { return std::log(d / s.median) / s.sigma; }

// Share of the area distribution (untruncated) below d.
double area_cdf(const SpeciesDef& s, double d) {
  if (s.distribution == SizeDistribution::lognormal) return normal_cdf(z_of(s, d));
  return d;  // uniform: proportional to d (only differences are used)
}

}  // namespace

std::vector<SpeciesDef> split_into_classes(const SpeciesDef& family, int classes) {
  std::vector<SpeciesDef> out;
  const double lo = family.min_diameter, hi = family.max_diameter;
  const double total = area_cdf(family, hi) - area_cdf(family, lo);
  for (int k = 0; k < classes; ++k) {
    SpeciesDef c = family;
    c.min_diameter = k == 0 ? lo : lo * std::pow(hi / lo, static_cast<double>(k) / classes);
    c.max_diameter = k + 1 == classes ? hi : lo * std::pow(hi / lo, static_cast<double>(k + 1) / classes);
    c.diameter = std::sqrt(c.min_diameter * c.max_diameter);
    c.area_share = total > 0 ? family.area_share * (area_cdf(family, c.max_diameter) - area_cdf(family, c.min_diameter)) / total
                             : family.area_share / classes;
    if (classes > 1) c.name = family.name + "_" + std::to_string(k + 1);
    out.push_back(c);
  }
  return out;
}

double mean_inverse_square_diameter(const SpeciesDef& s) {
  const double a = s.min_diameter, b = s.max_diameter;
  switch (s.distribution) {
    case SizeDistribution::spread: return 1.0 / (s.diameter * s.diameter);
    case SizeDistribution::uniform: return 1.0 / (a * b);  // (1/(b-a)) ∫ d^-2 dd
    case SizeDistribution::lognormal: {
      // Truncated lognormal moment E[d^k] with k = -2: m^k e^(k^2 s^2 / 2) times the ratio of
      // the truncation masses, shifted by k s.
      const double za = z_of(s, a), zb = z_of(s, b), sg = s.sigma;
      const double mass = normal_cdf(zb) - normal_cdf(za);
      return std::exp(2 * sg * sg) / (s.median * s.median) * (normal_cdf(zb + 2 * sg) - normal_cdf(za + 2 * sg)) / mass;
    }
  }
  return 0;
}

double smallest_diameter(const SpeciesDef& s) {
  return s.distribution == SizeDistribution::spread ? s.diameter : s.min_diameter;
}

std::vector<double> class_diameters(const SpeciesDef& s, int count) {
  std::vector<double> out;
  const double a = s.min_diameter, b = s.max_diameter;
  for (int k = 0; k < count; ++k) {
    const double u = (k + 0.5) / count;
    if (s.distribution == SizeDistribution::uniform) {
      // Number density ∝ d^-2 on [a, b]: F(d) = (1/a - 1/d) / (1/a - 1/b), inverted.
      out.push_back(1.0 / (1.0 / a - u * (1.0 / a - 1.0 / b)));
    } else {
      // Number density ∝ lognormal(median, sigma) / d^2: lognormal again, median e^(-2 s^2),
      // truncated to [a, b]; inverted by bisection in ln d (deterministic, 80 halvings).
      const double mu = std::log(s.median) - 2 * s.sigma * s.sigma;
      auto cdf = [&](double ln_d) { return normal_cdf((ln_d - mu) / s.sigma); };
      const double ca = cdf(std::log(a)), cb = cdf(std::log(b));
      const double target = ca + u * (cb - ca);
      double l = std::log(a), h = std::log(b);
      for (int i = 0; i < 80; ++i) {
        const double m = 0.5 * (l + h);
        (cdf(m) < target ? l : h) = m;
      }
      out.push_back(std::exp(0.5 * (l + h)));
    }
  }
  return out;
}

}  // namespace runout

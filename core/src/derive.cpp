#include "runout/derive.hpp"
#include "runout/size_distribution.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "runout/contact/registry.hpp"
#include "runout/errors.hpp"

namespace runout {

double peak_overlap_factor(double restitution) {
  if (restitution >= 1.0) return 1.0;
  const double beta = kPi / std::log(restitution);
  return std::exp(-std::atan(beta) / beta);
}

namespace {

// One dimensionless collision x'' = -max(0, x^a + c x^b x') from x = 0, x' = 1, with a = 3/2,
// b = 1/4 (Hertz) or a = 1, b = 0 (linear): returns {restitution, peak overlap}. RK4 with a step
// small against the contact time (about 3 units for c = 0).
std::pair<double, double> dashpot_collision(double c, bool hertz) {
  auto accel = [c, hertz](double x, double v) {
    const double xp = std::max(x, 0.0);
    const double f = hertz ? xp * std::sqrt(xp) + c * std::sqrt(std::sqrt(xp)) * v
                           : xp + c * v;
    return -std::max(f, 0.0);
  };
  double x = 0, v = 1, peak = 0;
  const double h = 2e-4;
  for (int n = 0; n < 10'000'000; ++n) {
    const double k1x = v, k1v = accel(x, v);
    const double k2x = v + 0.5 * h * k1v, k2v = accel(x + 0.5 * h * k1x, v + 0.5 * h * k1v);
    const double k3x = v + 0.5 * h * k2v, k3v = accel(x + 0.5 * h * k2x, v + 0.5 * h * k2v);
    const double k4x = v + h * k3v, k4v = accel(x + h * k3x, v + h * k3v);
    x += h / 6 * (k1x + 2 * k2x + 2 * k3x + k4x);
    v += h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
    peak = std::max(peak, x);
    // Contact ends when the (tension-free) force vanishes on the way out.
    if (v < 0 && (x <= 0 || accel(x, v) == 0.0)) return {-v, peak};
  }
  return {0.0, peak};
}

}  // namespace

DashpotDesign dashpot_design(double restitution, bool hertz) {
  if (restitution >= 1.0) return {0.0, dashpot_collision(0.0, hertz).second};
  double lo = 0, hi = 1;
  while (dashpot_collision(hi, hertz).first > restitution) hi *= 2;
  for (int it = 0; it < 50; ++it) {
    const double mid = 0.5 * (lo + hi);
    (dashpot_collision(mid, hertz).first > restitution ? lo : hi) = mid;
  }
  const double c = 0.5 * (lo + hi);
  return {c, dashpot_collision(c, hertz).second};
}

double sphere_mass(double radius, double density) {
  return 4.0 / 3.0 * kPi * radius * radius * radius * density;
}
double sphere_inertia(double mass, double radius) { return 0.4 * mass * radius * radius; }

namespace {

// The knobs of one interaction (SPEC §3); the laws derive their Params from them.
PairCoefficients make_pair(double r_star, double m_star, double restitution, double friction,
                           const ContactDef& contact, const DashpotDesign& dashpot,
                           double gravity) {
  PairCoefficients p;
  p.reduced_radius = r_star;
  p.reduced_mass = m_star;
  // k_U / m* = (g / r*) (alphadot0 / alphamax f)^2, SPEC §3.
  const double f = peak_overlap_factor(restitution);
  const double ratio = contact.design_impact_speed / contact.design_max_overlap * f;
  p.k_unload = m_star * gravity / r_star * ratio * ratio;
  p.k_load = restitution * restitution * p.k_unload;
  p.design_speed = contact.design_impact_speed * std::sqrt(gravity * r_star);
  p.design_overlap = contact.design_max_overlap * r_star;
  p.dashpot = dashpot;
  p.stiffness_ratio = contact.stiffness_ratio;
  p.k_tangential = contact.stiffness_ratio * p.k_load;
  p.friction = friction;
  p.rolling_friction = contact.rolling_friction;
  p.rolling_damping = contact.rolling_damping;
  NormalLaws::with(contact.normal_model, [&](auto law) {
    p.normal_stiffness_for_dt = decltype(law)::stiffness_for_dt(p);
  });
  TangentialLaws::with(contact.tangential_model, [&](auto law) {
    p.tangential_stiffness_for_dt = decltype(law)::stiffness_for_dt(p);
  });
  return p;
}

}  // namespace

ContactTable derive_contact_table(const MaterialDef& material, const ContactDef& contact,
                                  std::span<const SpeciesDef> species, double gravity) {
  ContactTable t;
  const int n = static_cast<int>(species.size());
  t.species_count = n;
  t.pair.resize(static_cast<size_t>(n * n));
  t.wall.resize(static_cast<size_t>(n));
  // Only the chosen law's dashpot is designed (a bisection over simulated collisions), once
  // per restitution.
  DashpotDesign design_pp, design_pw;
  NormalLaws::with(contact.normal_model, [&](auto law) {
    design_pp = decltype(law)::design(material.restitution);
    design_pw = material.wall_restitution == material.restitution
                    ? design_pp : decltype(law)::design(material.wall_restitution);
  });
  for (int a = 0; a < n; ++a) {
    const double ra = 0.5 * species[a].diameter;
    const double ma = sphere_mass(ra, material.density);
    for (int b = 0; b < n; ++b) {
      const double rb = 0.5 * smallest_diameter(species[b]);
      const double mb = sphere_mass(rb, material.density);
      t.pair[a * n + b] = make_pair(ra * rb / (ra + rb), ma * mb / (ma + mb),
                                    material.restitution, material.friction, contact, design_pp,
                                    gravity);
    }
    t.wall[a] = make_pair(ra, ma, material.wall_restitution, material.wall_friction, contact,
                          design_pw, gravity);
  }
  return t;
}

CollisionPeriods collision_periods(const ContactTable& table, std::span<const SpeciesDef> species,
                                   double density, int a, int b) {
  // The smallest disc of each species with the species' stiffness: the shortest period.
  const double ra = 0.5 * smallest_diameter(species[a]);
  const double mass = sphere_mass(ra, density), inertia = sphere_inertia(mass, ra);
  const PairCoefficients& c = b < 0 ? table.wall[a] : table.between(a, b);
  CollisionPeriods out;
  if (b < 0) {
    out.ring = 6.0;  // as stiff as an equal-disc ring (wall k = disc k)
  } else {
    // How many b-discs fit around one a-disc: 6 for equal sizes.
    const double rb = 0.5 * smallest_diameter(species[b]);
    out.ring = std::floor(kPi / std::asin(rb / (ra + rb)) + 1e-9);
  }
  const double k_n = c.normal_stiffness_for_dt, k_s = c.tangential_stiffness_for_dt;
  // Half of the ring acts along any one direction (6 -> 3 k, SPEC §3).
  out.translational = 2 * kPi * std::sqrt(mass / (0.5 * out.ring * (k_n + k_s)));
  out.rotational = 2 * kPi * std::sqrt(inertia / (out.ring * k_s * ra * ra));
  return out;
}

double minimum_collision_period(const ContactTable& table, std::span<const SpeciesDef> species,
                                double density, const std::vector<char>& present) {
  double tau = std::numeric_limits<double>::infinity();
  const int n = table.species_count;
  for (int a = 0; a < n; ++a) {
    if (!present[a]) continue;
    for (int b = -1; b < n; ++b) {
      if (b >= 0 && !present[b]) continue;
      const CollisionPeriods t = collision_periods(table, species, density, a, b);
      tau = std::min({tau, t.translational, t.rotational});
    }
  }
  return tau;
}

double unit_length(std::span<const SpeciesDef> species) {
  double d = std::numeric_limits<double>::infinity();
  for (const auto& s : species) d = std::min(d, s.diameter);
  return d;
}

double unit_time(std::span<const SpeciesDef> species, double gravity) {
  return std::sqrt(unit_length(species) / gravity);
}

}  // namespace runout

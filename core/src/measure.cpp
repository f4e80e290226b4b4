#include "runout/measure.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <tuple>

#include "runout/derive.hpp"

namespace runout {

Eigen::Vector2d centre_of_mass(const Particles& p) {
  double m = 0, mx = 0, my = 0;
  for (std::size_t k = 0; k < p.size(); ++k) {
    m += p.mass[k];
    mx += p.mass[k] * p.x[k];
    my += p.mass[k] * p.y[k];
  }
  if (m == 0) return {std::nan(""), std::nan("")};
  return {mx / m, my / m};
}

double translational_energy(const Particles& p) {
  double e = 0;
  for (std::size_t k = 0; k < p.size(); ++k)
    e += 0.5 * p.mass[k] * (p.vx[k] * p.vx[k] + p.vy[k] * p.vy[k]);
  return e;
}

double rotational_energy(const Particles& p) {
  double e = 0;
  for (std::size_t k = 0; k < p.size(); ++k)
    e += 0.5 / p.inv_inertia[k] * p.omega[k] * p.omega[k];
  return e;
}

double potential_energy(const Particles& p, double gravity) {
  double e = 0;
  for (std::size_t k = 0; k < p.size(); ++k) e += p.mass[k] * gravity * p.y[k];
  return e;
}

double height_above_bed(const std::vector<Segment>& segments, const Eigen::Vector2d& point) {
  double h = std::numeric_limits<double>::infinity();
  for (const auto& s : segments)
    if (s.bed) h = std::min(h, distance_to(s, point));
  return h;
}

SegregationHeights mean_heights(const Particles& p, const std::vector<Segment>& segments,
                                SpeciesRoles roles) {
  double hs = 0, hl = 0;
  std::size_t ns = 0, nl = 0;
  for (std::size_t k = 0; k < p.size(); ++k) {
    const double h = height_above_bed(segments, {p.x[k], p.y[k]});
    if (p.species[k] == roles.small) { hs += h; ++ns; }
    if (p.species[k] == roles.large) { hl += h; ++nl; }
  }
  return {ns ? hs / ns : std::nan(""), nl ? hl / nl : std::nan("")};
}

std::vector<double> mean_heights_by_species(const Particles& p, const std::vector<Segment>& segments,
                                            int species_count) {
  std::vector<double> sum(species_count, 0.0);
  std::vector<std::size_t> n(species_count, 0);
  for (std::size_t k = 0; k < p.size(); ++k) {
    sum[p.species[k]] += height_above_bed(segments, {p.x[k], p.y[k]});
    ++n[p.species[k]];
  }
  for (int s = 0; s < species_count; ++s) sum[s] = n[s] ? sum[s] / n[s] : std::nan("");
  return sum;
}

double basal_spin(const Particles& p, const std::vector<Segment>& segments, SpeciesRoles roles,
                  double unit_time) {
  double sum = 0;
  std::size_t n = 0;
  for (std::size_t k = 0; k < p.size(); ++k) {
    if (p.species[k] != roles.small) continue;
    if (height_above_bed(segments, {p.x[k], p.y[k]}) < p.radius[k]) {
      sum += p.omega[k] * unit_time;
      ++n;
    }
  }
  return n ? sum / n : std::nan("");
}

std::pair<double, double> deposit_extent(const Particles& p, double bin, double min_fill, int max_gap) {
  const std::size_t n = p.size();
  if (n == 0) return {0.0, 0.0};
  double xmin = p.x[0], xmax = p.x[0];
  for (std::size_t k = 0; k < n; ++k) { xmin = std::min(xmin, p.x[k]); xmax = std::max(xmax, p.x[k]); }
  const int nbins = std::max(1, static_cast<int>(std::floor((xmax - xmin) / bin)) + 1);
  std::vector<double> fill(nbins, 0.0);
  for (std::size_t k = 0; k < n; ++k)
    fill[std::min(nbins - 1, static_cast<int>((p.x[k] - xmin) / bin))] += p.radius[k] * p.radius[k];
  const int fullest = static_cast<int>(std::max_element(fill.begin(), fill.end()) - fill.begin());
  auto counts = [&](int b) { return fill[b] > 0 && fill[b] >= min_fill * fill[fullest]; };
  auto extend = [&](int from, int step) {
    int last = from;
    for (int b = from + step, gap = 0; b >= 0 && b < nbins; b += step) {
      if (counts(b)) { last = b; gap = 0; }
      else if (++gap > max_gap) break;
    }
    return last;
  };
  const int first = extend(fullest, -1), last = extend(fullest, +1);
  return {xmin + first * bin, xmin + (last + 1) * bin};
}

BasalLayer basal_layer(const Particles& p, const std::vector<Segment>& segments,
                       SpeciesRoles roles, double large_diameter, double packing) {
  BasalLayer out;
  const std::size_t n = p.size();
  out.member.assign(n, 0);
  if (n == 0) return out;

  // L1: the deposit without its scattered ends.
  std::tie(out.deposit_start, out.deposit_end) = deposit_extent(p, large_diameter, 0.1, 0);

  // Lower contour: per bin of width D, the bottom edge height of the lowest large disc.
  const double x0 = out.deposit_start;
  const int bins = std::max(1, static_cast<int>(std::ceil((out.deposit_end - x0) / large_diameter)));
  std::vector<double> contour(bins, std::numeric_limits<double>::infinity());
  std::vector<double> height(n);
  for (std::size_t k = 0; k < n; ++k) height[k] = height_above_bed(segments, {p.x[k], p.y[k]});
  const bool has_large = roles.large != roles.small;
  if (has_large) {
    for (std::size_t k = 0; k < n; ++k) {
      if (p.species[k] == roles.small) continue;  // every larger disc (bidisperse: the large)
      const int b = static_cast<int>(std::floor((p.x[k] - x0) / large_diameter));
      if (b < 0 || b >= bins) continue;
      contour[b] = std::min(contour[b], height[k] - p.radius[k]);
    }
  }
  // Contour through bin centres, linear in between; a bin with no large disc takes its
  // neighbours' interpolation (an all-small stretch keeps the layer open above).
  std::vector<double> bx, by;
  for (int b = 0; b < bins; ++b)
    if (std::isfinite(contour[b])) { bx.push_back(x0 + (b + 0.5) * large_diameter); by.push_back(contour[b]); }
  auto contour_at = [&](double x) {
    if (bx.empty()) return -std::numeric_limits<double>::infinity();
    if (x <= bx.front()) return by.front();
    if (x >= bx.back()) return by.back();
    const auto it = std::upper_bound(bx.begin(), bx.end(), x);
    const std::size_t hi = static_cast<std::size_t>(it - bx.begin()), lo = hi - 1;
    const double w = (x - bx[lo]) / (bx[hi] - bx[lo]);
    return by[lo] + w * (by[hi] - by[lo]);
  };
  if (has_large) {
    for (std::size_t k = 0; k < n; ++k) {
      if (p.species[k] != roles.small) continue;
      if (p.x[k] < out.deposit_start || p.x[k] > out.deposit_end) continue;
      if (height[k] < contour_at(p.x[k])) out.member[k] = 1;
    }
  }

  // H_layer for the four windows centred on the deposit centroid (eq. 4.9): the centroid of
  // the deposit body, so scattered discs do not pull the windows off it.
  double body_mass = 0, body_x = 0;
  for (std::size_t k = 0; k < n; ++k)
    if (p.x[k] >= out.deposit_start && p.x[k] <= out.deposit_end) { body_mass += p.mass[k]; body_x += p.mass[k] * p.x[k]; }
  const double centre = body_mass > 0 ? body_x / body_mass : centre_of_mass(p).x();
  const double l1 = std::max(out.deposit_end - out.deposit_start, 1e-12);
  const std::array<double, 4> fractions{1.0, 0.75, 0.5, 0.25};
  for (int w = 0; w < 4; ++w) {
    const double half = 0.5 * fractions[w] * l1;
    double area = 0;
    for (std::size_t k = 0; k < n; ++k)
      if (out.member[k] && std::abs(p.x[k] - centre) <= half) area += kPi * p.radius[k] * p.radius[k];
    out.thickness[w] = area / (2 * half * packing);
  }
  const auto [mn, mx] = std::minmax_element(out.thickness.begin(), out.thickness.end());
  out.mean_thickness = (out.thickness[0] + out.thickness[1] + out.thickness[2] + out.thickness[3]) / 4;
  out.spread = 0.5 * (*mx - *mn);
  return out;
}

FrontReach highest_point(const Particles& p) {
  FrontReach f{0, -std::numeric_limits<double>::infinity()};
  for (std::size_t k = 0; k < p.size(); ++k)
    if (p.y[k] + p.radius[k] > f.top_y) { f.top_y = p.y[k] + p.radius[k]; f.top_x = p.x[k]; }
  return f;
}

double farthest_edge_x(const Particles& p) {
  double x = -std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < p.size(); ++k) x = std::max(x, p.x[k] + p.radius[k]);
  return x;
}

double mass_kinetic_energy(const Particles& p, const PairContacts& c) {
  std::vector<char> in_mass(p.size(), 0);
  for (std::size_t q = 0; q < c.size(); ++q) {
    const std::int32_t i = c.i[q], j = c.j[q];
    const double dx = p.x[j] - p.x[i], dy = p.y[j] - p.y[i], rsum = p.radius[i] + p.radius[j];
    if (dx * dx + dy * dy < rsum * rsum) in_mass[i] = in_mass[j] = 1;
  }
  // A scene that is mostly lone discs (one disc, a sparse spray) has no "mass" apart from its
  // discs: then every disc counts.
  std::size_t members = 0;
  for (char m : in_mass) members += m;
  const bool all = 2 * members < p.size();
  double e = 0;
  for (std::size_t k = 0; k < p.size(); ++k)
    if (all || in_mass[k]) e += 0.5 * p.mass[k] * (p.vx[k] * p.vx[k] + p.vy[k] * p.vy[k]);
  return e;
}

}  // namespace runout

// The keys of a scene file's flat tables, each listed once: its name, the member it sets, the
// values it allows and what it means. One list drives the reader (types, ranges, the keys an
// unknown key is told about), the writer (scene.resolved.toml, the physics and pile keys) and
// `runout keys`. A visitor V is called once per key, in the order listed:
//   v.number(key, double&, Range, meaning)         v.integer(key, Int&, lo, hi, meaning)
//   v.choice(key, T&, Options, meaning)            v.flags(key, Flags&, names, meaning)
// The tables with structure ([species.NAME], [[walls]], [[particles]]) are read in scene_file.cpp.
#pragma once

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "runout/contact/registry.hpp"
#include "runout/scene.hpp"

namespace runout::io {

inline constexpr double kInf = std::numeric_limits<double>::infinity();

// The shortest text that reads back as the same double (the -0.1 a user typed is "-0.1", not
// -0.10000000000000001, and no two different values print alike); whole numbers in full.
inline std::string format_number(double v) {
  char buf[48];
  if (std::isfinite(v) && v == std::floor(v) && std::abs(v) < 1e15) {
    std::snprintf(buf, sizeof buf, "%.0f", v);
    return buf;
  }
  for (int digits = 1; digits <= 17; ++digits) {
    std::snprintf(buf, sizeof buf, "%.*g", digits, v);
    if (std::strtod(buf, nullptr) == v) break;
  }
  return buf;
}

// A numeric interval with open or closed ends, printed the way a user reads it: "(0, 1]".
struct Range {
  double lo = -kInf, hi = kInf;
  bool lo_open = false, hi_open = false;
  bool contains(double v) const {
    return (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
  }
  std::string text() const {
    auto end = [](double v) { return std::isinf(v) ? std::string(v < 0 ? "-inf" : "inf") : format_number(v); };
    return std::string(lo_open || std::isinf(lo) ? "(" : "[") + end(lo) + ", " + end(hi) +
           (hi_open || std::isinf(hi) ? ")" : "]");
  }
};
inline Range closed(double lo, double hi) { return {lo, hi, false, false}; }
inline Range positive(double hi = kInf) { return {0, hi, true, false}; }

template <class T>
using Options = std::vector<std::pair<std::string, T>>;

// The contact laws' names come from their registry (contact/registry.hpp).
template <class Laws>
Options<std::string> law_choices() {
  Options<std::string> v;
  for (const auto& name : Laws::names()) v.emplace_back(name, name);
  return v;
}
inline const Options<WallInside> kWallSides = {
    {"left", WallInside::left}, {"right", WallInside::right}, {"both", WallInside::both}};
inline const Options<SizeDistribution> kDistributions = {
    {"uniform", SizeDistribution::uniform}, {"lognormal", SizeDistribution::lognormal}};
inline const Options<IntegratorKind> kIntegrators = {
    {"symplectic_euler", IntegratorKind::symplectic_euler},
    {"velocity_verlet", IntegratorKind::velocity_verlet}};

// The names of output.series.
inline constexpr std::pair<const char*, bool SeriesSelection::*> kSeriesNames[] = {
    {"energy", &SeriesSelection::energy}, {"segregation", &SeriesSelection::segregation},
    {"basal_spin", &SeriesSelection::basal_spin}, {"front", &SeriesSelection::front},
    {"overlap", &SeriesSelection::overlap}};

// M is the section's struct, const or not: the same list is read into and written from.
template <class M, class V>
void material_keys(M& m, V& v) {
  v.number("density", m.density, positive(), "kg/m^3");
  v.number("friction", m.friction, closed(0, 100), "disc-disc Coulomb friction mu");
  v.number("wall_friction", m.wall_friction, closed(0, 100), "disc-wall Coulomb friction mu");
  // e_n below 0.01 means nothing numerically: Walton–Braun's loading slope e_n^2 k_U falls
  // under 1e-4 of its unloading one, and the dashpot laws' damping (designed by simulating
  // collisions, derive.cpp) grows without bound as e_n goes to 0.
  v.number("restitution", m.restitution, closed(0.01, 1), "disc-disc normal restitution e_n");
  v.number("wall_restitution", m.wall_restitution, closed(0.01, 1), "disc-wall normal restitution e_n");
}

template <class C, class V>
void contact_keys(C& c, V& v) {
  v.choice("normal_model", c.normal_model, law_choices<NormalLaws>(), "normal contact law");
  v.choice("tangential_model", c.tangential_model, law_choices<TangentialLaws>(), "tangential contact law");
  v.choice("rolling_model", c.rolling_model, law_choices<RollingLaws>(), "rolling resistance law");
  v.number("design_impact_speed", c.design_impact_speed, positive(1e6),
           "impact speed the stiffness is designed for, in sqrt(g r*) (SPEC 3)");
  v.number("design_max_overlap", c.design_max_overlap, {0, 0.5, true, false},
           "largest overlap at that speed, share of r* (SPEC 3)");
  v.number("stiffness_ratio", c.stiffness_ratio, {0, 10, true, false}, "k_s / k_L");
  v.number("rolling_friction", c.rolling_friction, closed(0, 10), "mu_r: rolling torque limit over r* F_n");
  v.number("rolling_damping", c.rolling_damping, closed(0, 10), "eta_r: rolling dashpot over its critical value");
  v.number("overlap_guard", c.overlap_guard, {0, 1, true, false},
           "stop when an impact overlaps beyond this share of its pass-through depth");
}

template <class I, class V>
void integration_keys(I& i, V& v) {
  v.choice("integrator", i.integrator, kIntegrators, "time integrator");
  // Below 1e-4 of tau_min a collision takes over 60,000 steps and a run never ends in
  // practice (the stability limit, 1/pi, is checked with the setup).
  v.number("dt_fraction", i.dt_fraction, closed(1e-4, 1), "dt / tau_min (at most 1/pi: stability)");
  v.number("skin", i.skin, {0, 10, true, false}, "Verlet skin, in small diameters d");
  v.number("gravity", i.gravity, positive(1e4), "m/s^2");
}

template <class A, class V>
void avalanche_keys(A& a, V& v) {
  v.number("incline_angle", a.incline_angle_deg, {0, 90, true, true}, "degrees");
  v.number("incline_length", a.incline_length, {0, 1e5, false, false}, "gate to foot along the incline, in D");
  v.number("pile_width", a.pile_width, {0, 1e5, true, false}, "back wall to gate, in D");
  v.number("floor_length", a.floor_length, {0, 1e6, true, false}, "foot to end wall, in D");
  v.number("wall_height", a.wall_height, {0, 1e6, true, false}, "back wall, gate and end wall height, in D");
  v.integer("reference_large_count", a.reference_large_count, 1, 1e6,
            "N0: total disc area = area of N0 large discs (SPEC 5)");
}

template <class P, class V>
void preparation_keys(P& p, V& v) {
  v.integer("seed", p.seed, 0, 9.2e18, "random seed of the pile");
  v.number("initial_packing", p.initial_packing, {0, 0.9, true, false}, "disc area / box area when placed");
  v.number("initial_speed", p.initial_speed, closed(0, 100), "random speeds up to this, in sqrt(g d)");
  v.number("growth_time", p.growth_time, {0, 1e4, true, false}, "t*, e-folding time of the radius growth");
  v.number("settle_ek_threshold", p.settle_ek_threshold, {0, 1, true, false}, "settled when E_k/Ep below this ...");
  v.number("settle_hold", p.settle_hold, closed(0, 1e4), "... for this long (t*)");
  v.number("settle_max_time", p.settle_max_time, {0, 1e6, true, false}, "t*; not settled by then is an error");
  v.number("damping", p.damping, {0, 1, false, true}, "PFC local damping while settling");
}

template <class R, class V>
void rest_keys(R& r, V& v) {
  v.number("ek_threshold", r.ek_threshold, {0, 1, true, false}, "at rest when E_k/Ep0 below this ...");
  v.number("hold", r.hold, closed(0, 1e4), "... for this long (t*)");
  v.number("max_time", r.max_time, {0, 1e7, true, false}, "t*; not at rest by then ends the run");
}

template <class O, class V>
void output_keys(O& o, V& v) {
  v.flags("series", o.series, kSeriesNames, "analysis series computed and written");
  v.number("timeseries_every", o.timeseries_every, {0, 1e6, true, false}, "t* between time-series rows");
  v.number("checkpoint_every", o.checkpoint_every, closed(0, 1e7), "t* between checkpoints (0: off)");
  v.number("dump_every", o.dump_every, closed(0, 1e7), "t* between LAMMPS dump frames (0: off)");
  v.number("vtk_every", o.vtk_every, closed(0, 1e7), "t* between VTK frames (0: off)");
  v.number("end_time", o.end_time, closed(0, 1e7), "t*; > 0 stops the run there even if not at rest");
  v.number("basal_layer_packing", o.basal_layer_packing, {0, 1, true, false},
           "C in H_layer = pi sum r^2 / (L C) (SPEC 6)");
}

}  // namespace runout::io

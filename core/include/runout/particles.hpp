// Disc state as structure of arrays, laid out for the hot loops (SPEC §2: discs move in the
// plane but carry sphere mass and inertia).
#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

#include "runout/hot_array.hpp"

namespace runout {

struct Particles {
  // Hot: read or written every step.
  HotArray<double> x, y, vx, vy, omega;
  HotArray<double> radius, inv_mass, inv_inertia;
  HotArray<std::int32_t> species;
  // Velocity Verlet keeps the last acceleration between steps.
  HotArray<double> ax, ay, alpha;
  // Cold: bookkeeping and output (angle is drifted with the rest, hence hot storage too).
  HotArray<double> angle;  // accumulated rotation (rad), for drawing spokes
  std::vector<double> mass;
  std::vector<std::int64_t> id;

  std::size_t size() const { return x.size(); }

  // The one list of the per-disc arrays: f(name, array) for each array a checkpoint stores,
  // in the order it stores them, then (for_each_array) inv_mass, which is derived from mass.
  // Adding a disc, renumbering the discs and the checkpoint codec all go through it.
  template <class Self, class F>
  static void for_each_stored(Self& p, F&& f) {
    f("x", p.x); f("y", p.y); f("vx", p.vx); f("vy", p.vy); f("omega", p.omega);
    f("angle", p.angle); f("ax", p.ax); f("ay", p.ay); f("alpha", p.alpha);
    f("radius", p.radius); f("mass", p.mass); f("inv_inertia", p.inv_inertia);
    f("species", p.species); f("id", p.id);
  }
  // The arrays a deposit's measurements read (SPEC §6): what a run keeps of the discs when
  // the mass first came to rest (run.hpp), in for_each_stored's order, without the
  // accelerations, the angle and the inertia.
  static bool in_deposit(std::string_view name) {
    for (std::string_view left_out : {"angle", "ax", "ay", "alpha", "inv_inertia"})
      if (name == left_out) return false;
    return true;
  }
  template <class Self, class F>
  static void for_each_deposit(Self& p, F&& f) {
    for_each_stored(p, [&](const char* name, auto& v) {
      if (in_deposit(name)) f(name, v);
    });
  }
  template <class Self, class F>
  static void for_each_array(Self& p, F&& f) {
    for_each_stored(p, f);
    f("inv_mass", p.inv_mass);
  }

  void add(std::int64_t disc_id, int species_index, double px, double py, double r, double m,
           double inertia, double pvx = 0, double pvy = 0, double pomega = 0) {
    for_each_array(*this, [](const char*, auto& v) { v.emplace_back(); });  // zeros
    const std::size_t k = size() - 1;
    x[k] = px; y[k] = py; vx[k] = pvx; vy[k] = pvy; omega[k] = pomega; radius[k] = r;
    inv_mass[k] = 1.0 / m; inv_inertia[k] = 1.0 / inertia; species[k] = species_index;
    mass[k] = m; id[k] = disc_id;
  }
};

}  // namespace runout

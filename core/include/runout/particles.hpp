// Disc state as structure of arrays, laid out for the hot loops (SPEC §2: discs move in the
// plane but carry sphere mass and inertia).
#pragma once

#include <cstdint>
#include <vector>

namespace runout {

struct Particles {
  // Hot: read or written every step.
  std::vector<double> x, y, vx, vy, omega;
  std::vector<double> radius, inv_mass, inv_inertia;
  std::vector<std::int32_t> species;
  // Velocity Verlet keeps the last acceleration between steps.
  std::vector<double> ax, ay, alpha;
  // Cold: bookkeeping and output.
  std::vector<double> angle;  // accumulated rotation (rad), for drawing spokes
  std::vector<double> mass;
  std::vector<std::int64_t> id;

  std::size_t size() const { return x.size(); }

  void add(std::int64_t disc_id, int species_index, double px, double py, double r, double m,
           double inertia, double pvx = 0, double pvy = 0, double pomega = 0) {
    x.push_back(px); y.push_back(py); vx.push_back(pvx); vy.push_back(pvy);
    omega.push_back(pomega); radius.push_back(r);
    inv_mass.push_back(1.0 / m); inv_inertia.push_back(1.0 / inertia);
    species.push_back(species_index);
    ax.push_back(0); ay.push_back(0); alpha.push_back(0);
    angle.push_back(0); mass.push_back(m); id.push_back(disc_id);
  }
};

}  // namespace runout

// Small builders shared by the physics tests: one scene, two discs, one wall.
#pragma once

#include "runout/setup.hpp"

namespace runout::testing {

inline SceneDef two_species_scene(double d_large = 1.0, double d_small = 1.0) {
  SceneDef s;
  s.species = {{"large", d_large, 0.0, 0.0}, {"small", d_small, 0.0, 0.0}};
  return s;
}

inline ParticleDef disc(double x, double y, double diameter, int species = 0, double vx = 0,
                        double vy = 0, double omega = 0) {
  ParticleDef p;
  p.x = x; p.y = y; p.vx = vx; p.vy = vy; p.omega = omega;
  p.diameter = diameter;
  p.species = species;
  return p;
}

}  // namespace runout::testing

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

// The scene's explicit world with gravity switched off (binary collisions, impacts); the
// stiffness is still derived with g, as SPEC §3 does.
inline World zero_gravity_world(const SceneDef& scene, bool track_energy = false) {
  const SceneSetup setup = derive_setup(scene);
  const World w = build_explicit_world(scene, setup, 1);
  StepSettings st = w.settings();
  st.gravity = {0, 0};
  st.track_energy = track_energy;
  return World(w.particles(), w.segments(), w.table(), st);
}

// Steps until a contact has started and ended again (`in_contact` reads this step's force).
template <class InContact>
void step_through_one_contact(World& w, const InContact& in_contact) {
  bool touched = false;
  for (int n = 0; n < 5'000'000; ++n) {
    w.step();
    const bool force = in_contact(w);
    touched |= force;
    if (touched && !force) return;
  }
}

// The thesis geometry shrunk for a test (lengths in large diameters, SPEC §5).
inline AvalancheDef short_avalanche(double incline_length, double pile_width, double floor_length,
                                    double wall_height, int reference_large_count) {
  AvalancheDef a;
  a.incline_length = incline_length;
  a.pile_width = pile_width;
  a.floor_length = floor_length;
  a.wall_height = wall_height;
  a.reference_large_count = reference_large_count;
  return a;
}

// A small thesis-like pile (30 large-disc areas, D/d = 2) that settles in well under a second.
inline SceneDef small_pile() {
  SceneDef s;
  s.species = {{"large", 1.0, 0.1, 0.6}, {"small", 0.5, 0.1, 0.4}};
  s.avalanche = short_avalanche(6.0, 4.0, 20.0, 15.0, 30);
  s.preparation.settle_ek_threshold = 1e-5;
  return s;
}

// A pile of some 300 discs: enough that two or three threads' blocks each hold several
// windows of discs and pairs cross from one block to the next (World's Handoff).
inline SceneDef medium_pile() {
  SceneDef s = small_pile();
  s.avalanche = short_avalanche(12.0, 10.0, 40.0, 30.0, 150);
  return s;
}

}  // namespace runout::testing

// Checkpoints: a run resumed from one continues bit for bit as if never stopped; a damaged,
// truncated or foreign file is refused with a clear error, never half-read.
#include <gtest/gtest.h>

#include <cmath>

#include "runout/checkpoint.hpp"
#include "runout/errors.hpp"
#include "runout/setup.hpp"
#include "test_helpers.hpp"

namespace runout {
namespace {

void advance(World& w, double seconds) {
  while (w.time() < seconds) w.step();
}

TEST(Checkpoint, ResumeIsBitIdentical) {
  // Frictionless too: its checkpoints carry no tangential springs (World::frictional).
  for (auto [integrator, mu] : {std::pair{IntegratorKind::symplectic_euler, 0.5}, std::pair{IntegratorKind::velocity_verlet, 0.5},
                                std::pair{IntegratorKind::symplectic_euler, 0.0}}) {
    SceneDef s = testing::small_pile();
    s.integration.integrator = integrator;
    s.material.friction = s.material.wall_friction = mu;
    const SceneSetup setup = derive_setup(s);
    World straight = build_settled_pile(s, setup, 1);
    release(straight, setup);
    World resumed = straight;
    const double half = 2.0 * setup.unit_time, end = 4.0 * setup.unit_time;

    advance(straight, end);
    advance(resumed, half);
    const std::string bytes = encode_checkpoint(resumed, 42, "run state");
    World fresh = build_explicit_world(s, setup, 2);  // other thread count on purpose
    EXPECT_EQ(decode_checkpoint(bytes, 42, fresh, "test.ckpt"), "run state");
    EXPECT_EQ(fresh.step_count(), resumed.step_count());
    advance(fresh, end);
    ASSERT_EQ(fresh.particles().size(), straight.particles().size());
    for (std::size_t k = 0; k < fresh.particles().size(); ++k) {
      ASSERT_EQ(fresh.particles().x[k], straight.particles().x[k]) << "disc " << k;
      ASSERT_EQ(fresh.particles().vy[k], straight.particles().vy[k]) << "disc " << k;
      ASSERT_EQ(fresh.particles().omega[k], straight.particles().omega[k]) << "disc " << k;
    }
  }
}

TEST(Checkpoint, DamageIsDetected) {
  const SceneDef s = testing::small_pile();
  const SceneSetup setup = derive_setup(s);
  World w = build_settled_pile(s, setup, 1);
  const std::string good = encode_checkpoint(w, 7, "");
  World target = build_explicit_world(s, setup, 1);
  EXPECT_NO_THROW(decode_checkpoint(good, 7, target, "ok.ckpt"));

  std::string flipped = good;
  flipped[flipped.size() / 2] ^= 0x10;
  EXPECT_THROW(decode_checkpoint(flipped, 7, target, "flipped.ckpt"), IoError);
  EXPECT_THROW(decode_checkpoint(good.substr(0, good.size() - 9), 7, target, "short.ckpt"), IoError);
  EXPECT_THROW(decode_checkpoint("not a checkpoint at all, just text", 7, target, "text.ckpt"), IoError);
  try {
    decode_checkpoint(good, 8, target, "other.ckpt");
    FAIL() << "a checkpoint of another scene was accepted";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("different scene"), std::string::npos) << e.what();
  }
  std::string other_version = good;
  other_version[8] = 99;  // version field follows the 8-byte magic
  EXPECT_THROW(decode_checkpoint(other_version, 7, target, "v99.ckpt"), IoError);
}

// A well-sealed file (right checksum) whose values would crash or poison a run is refused by
// name: the checksum says the bytes are the ones written, not that they are sane.
TEST(Checkpoint, InsaneValuesAreRefused) {
  const SceneDef s = testing::small_pile();
  const SceneSetup setup = derive_setup(s);
  const World good = build_settled_pile(s, setup, 1);
  struct Case { const char* what; void (*spoil)(Particles&); const char* message; };
  const Case cases[] = {
      {"NaN x", [](Particles& p) { p.x[3] = std::nan(""); }, "non-finite position"},
      {"infinite vy", [](Particles& p) { p.vy[0] = HUGE_VAL; }, "non-finite position"},
      {"zero mass", [](Particles& p) { p.mass[1] = 0; }, "mass of disc 1"},
      {"negative radius", [](Particles& p) { p.radius[2] = -1e-3; }, "radius of disc 2"},
      {"species out of range", [](Particles& p) { p.species[0] = 7; }, "species of disc 0"},
  };
  for (const Case& c : cases) {
    Particles p = good.particles();
    c.spoil(p);
    const World bad(p, good.segments(), good.table(), good.settings());
    const std::string bytes = encode_checkpoint(bad, 7, "");
    World target = build_explicit_world(s, setup, 1);
    try {
      decode_checkpoint(bytes, 7, target, "bad.ckpt");
      ADD_FAILURE() << c.what << " was accepted";
    } catch (const IoError& e) {
      EXPECT_NE(std::string(e.what()).find("bad.ckpt"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(c.message), std::string::npos) << c.what << ": " << e.what();
    }
  }
}

// A NaN that gets past every check still stops at the neighbour search with an error, not a
// crash or an endless loop in the cell grid.
TEST(Checkpoint, NeighbourSearchRefusesNonFinitePositions) {
  const SceneDef s = testing::small_pile();
  const SceneSetup setup = derive_setup(s);
  const World good = build_settled_pile(s, setup, 1);
  for (double v : {std::nan(""), -HUGE_VAL}) {
    Particles p = good.particles();
    p.x[5] = v;
    World w(p, good.segments(), good.table(), good.settings());
    EXPECT_THROW(w.step(), NumericalError) << v;
  }
  // Far but finite: the grid is counted in floating point, so this steps (the run's escape
  // check is what reports it) instead of overflowing the cell count.
  Particles p = good.particles();
  p.x[5] = 1e308;
  World far(p, good.segments(), good.table(), good.settings());
  EXPECT_NO_THROW(far.step());
  EXPECT_THROW(far.check_escape(0.0), NumericalError);
}

}  // namespace
}  // namespace runout

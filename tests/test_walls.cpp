// Walls that no disc passes through (walls.hpp, SPEC §2): one-sided faces push a disc pressed
// past their line back to the inside; corners of the thesis container act as faces, not
// points, where they are concave; discs driven into the corners, pinched there by a heavy
// disc, or squeezed behind the back wall by a growing D/d = 8.33 pile never end outside.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "runout/errors.hpp"
#include "runout/setup.hpp"
#include "test_helpers.hpp"

namespace runout {
namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

// A single disc above a floor from x = -5 to 5, no gravity, its centre `depth` radii below the
// floor's line (overlap (1 + depth) r), at rest. The wall contact is elastic (e_n = 1): with
// e_n = 0.2 Walton–Braun would leave the disc dented in at 96 % of the overlap, force-free.
SceneDef pressed_into_floor(double depth, WallInside inside) {
  SceneDef s;
  s.species = {{"disc", 0.5, 0.0, 0.0}};
  s.material.wall_restitution = 1.0;
  s.walls = {{"floor", {{-5.0, 0.0}, {5.0, 0.0}}, true, inside}};
  s.particles = {testing::disc(0.0, -depth * 0.25, 0.5)};
  return s;
}

TEST(Walls, DiscPressedPastTheLineIsExpelledToTheInside) {
  // Overlap 1.5 r: the centre is half a radius below the floor. A one-sided floor pushes it
  // up; a two-sided plate pushes it down and out the far side (what the thesis container
  // must never do).
  for (auto [inside, up] : {std::pair{WallInside::left, true}, std::pair{WallInside::both, false}}) {
    World w = testing::zero_gravity_world(pressed_into_floor(0.5, inside));
    testing::step_through_one_contact(
        w, [](const World& v) { return v.wall_contacts().size() > 0 && v.wall_contacts().fy[0] != 0.0; });
    const Particles& p = w.particles();
    if (up) {
      EXPECT_GT(p.y[0], 0.25) << "clear of the floor, on its inside";
      EXPECT_GT(p.vy[0], 0.0);
    } else {
      EXPECT_LT(p.y[0], -0.25) << "a thin plate lets it out the far side";
      EXPECT_LT(p.vy[0], 0.0);
    }
  }
}

TEST(Walls, OneSidedGapIsSignedAndActsUpToADiameterBehind) {
  const Segment floor = make_segments({{"floor", {{-5.0, 0.0}, {5.0, 0.0}}, true, WallInside::left}})[0];
  const double r = 0.25;
  for (double y : {0.2, 0.0, -0.1, -0.3, -0.49}) {
    const WallTouch t = wall_touch(floor, {1.0, y}, r);
    EXPECT_TRUE(t.acts) << y;
    EXPECT_DOUBLE_EQ(t.gap, y);
    EXPECT_EQ(t.normal, Eigen::Vector2d(0.0, -1.0));
  }
  EXPECT_FALSE(wall_touch(floor, {1.0, -0.51}, r).acts) << "more than a diameter behind: let go";
  // "right" is the other side of the same line.
  const Segment ceiling = make_segments({{"c", {{-5.0, 0.0}, {5.0, 0.0}}, false, WallInside::right}})[0];
  EXPECT_DOUBLE_EQ(wall_touch(ceiling, {1.0, -0.1}, r).gap, 0.1);
  EXPECT_DOUBLE_EQ(wall_touch(ceiling, {1.0, 0.1}, r).gap, -0.1);
  // Beyond a free end the end is a point contact.
  const WallTouch end = wall_touch(floor, {5.3, 0.4}, r);
  EXPECT_TRUE(end.acts);
  EXPECT_DOUBLE_EQ(end.gap, 0.5);
}

// The thesis container of a small scene: incline + floor (bed), back wall, gate, end wall.
SceneSetup container(double ratio = 2.0) {
  SceneDef s = testing::small_pile();
  s.species[1].diameter = 1.0 / ratio;
  return derive_setup(s);
}

TEST(Walls, ThesisContainerCornersAreFacesWhereConcave) {
  const std::vector<Segment> seg = make_segments(container().walls);
  ASSERT_EQ(seg.size(), 5u);  // incline, floor, back wall, gate, end wall
  const Segment &incline = seg[0], &floor = seg[1], &back = seg[2], &gate = seg[3], &end = seg[4];
  for (const auto& s : seg) EXPECT_TRUE(s.one_sided());
  // Inside normals point to the discs: above the bed, right of the back wall, left of the
  // gate and of the end wall.
  EXPECT_NEAR(incline.inside.x(), std::sin(30 * kDeg), 1e-12);
  EXPECT_NEAR(incline.inside.y(), std::cos(30 * kDeg), 1e-12);
  EXPECT_EQ(floor.inside, Eigen::Vector2d(0, 1));
  EXPECT_EQ(back.inside, Eigen::Vector2d(1, 0));
  EXPECT_EQ(gate.inside, Eigen::Vector2d(-1, 0));
  EXPECT_EQ(end.inside, Eigen::Vector2d(-1, 0));
  // Concave corners (back wall foot 120 deg, incline foot 150 deg, floor end 90 deg) and the
  // gate's foot standing on the incline are no point contacts; the wall tops are.
  EXPECT_FALSE(incline.cap_a); EXPECT_FALSE(back.cap_b);
  EXPECT_FALSE(incline.cap_b); EXPECT_FALSE(floor.cap_a);
  EXPECT_FALSE(floor.cap_b); EXPECT_FALSE(end.cap_a);
  EXPECT_FALSE(gate.cap_a);
  EXPECT_TRUE(back.cap_a); EXPECT_TRUE(gate.cap_b); EXPECT_TRUE(end.cap_b);
  // Behind a concave corner exactly one face owns each point (the bisector splits it).
  for (const auto& [a, b] : {std::pair{&floor, &end}, std::pair{&incline, &floor}, std::pair{&back, &incline}}) {
    const Eigen::Vector2d v = a->b == b->a ? a->b : a->a;
    for (double angle = 0; angle < 360; angle += 7.5)
      for (double dist : {0.01, 0.05, 0.1}) {
        const Eigen::Vector2d p = v + dist * Eigen::Vector2d(std::cos(angle * kDeg), std::sin(angle * kDeg));
        const bool behind_both = (p - a->a).dot(a->inside) < 0 && (p - b->a).dot(b->inside) < 0;
        if (!behind_both) continue;
        const int acting = int(wall_touch(*a, p, 0.25).acts) + int(wall_touch(*b, p, 0.25).acts);
        EXPECT_EQ(acting, 1) << "angle " << angle << " dist " << dist;
      }
  }
}

// The thesis container with the given discs in it (no preparation); gravity on.
World container_world(const SceneSetup& setup, const Particles& discs, double skin_d = 0.2) {
  SceneDef s = testing::small_pile();
  s.integration.skin = skin_d;
  StepSettings st = step_settings(s, setup, 1);
  st.reorder_every = 0;
  return World(discs, make_segments(setup.walls), setup.table, st);
}

// Whether a centre is inside the container: on the inner side of the bed and of the back and
// end walls (x = 0 at the incline's foot, the floor at y = 0).
bool inside_container(const SceneSetup& setup, double x, double y) {
  const std::vector<Segment> seg = make_segments(setup.walls);
  const double bed = x < 0 ? -x * std::tan(30 * kDeg) : 0.0;
  return y > bed - 1e-9 && x > seg[2].a.x() && x < seg[4].a.x();
}

Particles one_disc(const SceneSetup& setup, int species, Eigen::Vector2d at, Eigen::Vector2d v) {
  Particles p;
  const double r = 0.5 * (species == 0 ? 1.0 : setup.unit_length);
  const double m = sphere_mass(r, 2500.0);
  p.add(1, species, at.x(), at.y(), r, m, sphere_inertia(m, r), v.x(), v.y());
  return p;
}

TEST(Walls, DiscsDrivenIntoTheCornersNeverEndOutside) {
  const SceneSetup setup = container(4.0);
  const std::vector<Segment> seg = make_segments(setup.walls);
  const double r = 0.5 * setup.unit_length;
  const double design = 10.0 * std::sqrt(9.81 * r);  // alphadot0 sqrt(g r*) against a wall
  // The incline's foot (150 deg) and the back wall's foot (120 deg), approached from every
  // direction inside the corner, at up to three times the design impact speed.
  struct Corner { Eigen::Vector2d vertex, face_a, face_b; };
  const Corner corners[] = {{seg[0].b, seg[0].inside, seg[1].inside}, {seg[2].b, seg[2].inside, seg[0].inside}};
  int runs = 0;
  for (const Corner& c : corners) {
    const Eigen::Vector2d bisector = (c.face_a + c.face_b).normalized();  // into the corner's inside
    for (double turn = -50; turn <= 50; turn += 20)
      for (double speed : {0.3, 1.0, 3.0}) {
        const Eigen::Rotation2Dd rot(turn * kDeg);
        const Eigen::Vector2d from = c.vertex + 3 * r * (rot * bisector);
        World w = container_world(setup, one_disc(setup, 1, from, -speed * design * (rot * bisector)));
        for (int n = 0; n < 20000; ++n) {
          w.step();
          ASSERT_TRUE(inside_container(setup, w.particles().x[0], w.particles().y[0]))
              << "corner at " << c.vertex.transpose() << ", turn " << turn << ", speed " << speed
              << "x design, step " << n;
        }
        ++runs;
      }
  }
  EXPECT_EQ(runs, 2 * 6 * 3);
}

TEST(Walls, SmallDiscPinchedInACornerByAHeavyDiscStaysInside) {
  // D/d = 8.33: a large disc 578 times heavier drops onto a small disc lying in the incline's
  // foot. Through a two-sided wall the squeezed small disc would pop out once its overlap
  // passed its radius; one-sided faces keep it in, whatever the skin.
  const SceneSetup setup = container(8.33);
  const std::vector<Segment> seg = make_segments(setup.walls);
  const double r = 0.5 * setup.unit_length;
  const Eigen::Vector2d corner = seg[0].b;
  const Eigen::Vector2d bisector = (seg[0].inside + seg[1].inside).normalized();
  for (double speed : {1.0, 3.0, 6.0}) {
    std::vector<double> trajectory[2];
    int k = 0;
    for (double skin : {0.1, 0.4}) {
      Particles p = one_disc(setup, 1, corner + 1.05 * r / std::cos(15 * kDeg) * bisector, {0, 0});
      const Particles large = one_disc(setup, 0, corner + (2.2 * r + 0.5) * bisector, -speed * bisector);
      p.add(2, 0, large.x[0], large.y[0], large.radius[0], large.mass[0], 1.0 / large.inv_inertia[0],
            large.vx[0], large.vy[0]);
      World w = container_world(setup, p, skin);
      for (int n = 0; n < 20000; ++n) {
        w.step();
        const auto& q = w.particles();
        ASSERT_TRUE(inside_container(setup, q.x[0], q.y[0]) && inside_container(setup, q.x[1], q.y[1]))
            << "speed " << speed << " m/s, skin " << skin << ", step " << n << ": small disc at ("
            << q.x[0] << ", " << q.y[0] << ")";
        trajectory[k].push_back(q.x[0]);
        trajectory[k].push_back(q.y[0]);
      }
      ++k;
    }
    // Behind-the-line contacts are listed in time: the skin changes nothing.
    EXPECT_EQ(trajectory[0], trajectory[1]) << "speed " << speed;
  }
}

TEST(Walls, GrowingSizeRatioEightPileBehindTheBackWallLosesNoDisc) {
  // The thesis's headline ratio, D/d = 8.33, %A_p = 25, in a narrow box so many small discs
  // grow against the back wall, squeezed there by growing large discs (how discs used to be
  // lost through it, SPEC §5 preparation).
  SceneDef s;
  s.species = {{"large", 1.0, 0.1, 0.75}, {"small", 0.12, 0.1, 0.25}};
  s.avalanche = testing::short_avalanche(4.0, 4.0, 10.0, 30.0, 24);  // 18 large, 417 small discs
  s.preparation.settle_ek_threshold = 1e-4;  // growth is the test, not the last ringing
  const SceneSetup setup = derive_setup(s);
  ASSERT_EQ(setup.counts[0] + setup.counts[1], 18 + 417);
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    s.preparation.seed = seed;
    const World w = build_settled_pile(s, setup, 1);
    const auto& p = w.particles();
    ASSERT_EQ(p.size(), 435u);
    for (std::size_t k = 0; k < p.size(); ++k)
      EXPECT_TRUE(inside_container(setup, p.x[k], p.y[k])) << "seed " << seed << ", disc " << p.id[k];
  }
}

TEST(Preparation, RingingPileSettlesWithinTheTimeLimit) {
  // Perfectly elastic, frictionless discs (e_n = 1, mu = 0) cannot lose energy: undamped, the
  // pile never comes to rest (it stays a gas of bouncing discs). The preparation's local damping settles it, and the pile then stays
  // below the threshold for settle_hold t* under the undamped law before it is released.
  SceneDef s = testing::small_pile();
  s.material.restitution = s.material.wall_restitution = 1.0;
  s.material.friction = s.material.wall_friction = 0.0;
  s.preparation.settle_ek_threshold = 1e-7;
  s.preparation.settle_max_time = 200.0;
  s.avalanche->wall_height = 60.0;  // elastic discs bounce high while the pile grows
  const SceneSetup setup = derive_setup(s);
  SettleReport report;
  build_settled_pile(s, setup, 1, {}, &report);
  EXPECT_LT(report.t_star_settled, 200.0);
  EXPECT_GT(report.t_star_settled, report.t_star_grown);
  EXPECT_LT(report.ek_over_ep_undamped, 1e-7);

  s.preparation.damping = 0.0;
  s.preparation.settle_max_time = 50.0;  // the undamped gas stays a gas (and later flies out)
  try {
    build_settled_pile(s, setup, 1);
    FAIL() << "an elastic pile settled without damping";
  } catch (const NumericalError& e) {
    EXPECT_NE(std::string(e.what()).find("did not settle"), std::string::npos) << e.what();
  }
}

TEST(Preparation, DampingIsGoneAtRelease) {
  SceneDef s = testing::small_pile();
  const SceneSetup setup = derive_setup(s);
  SettleReport report;
  World w = build_settled_pile(s, setup, 1, {}, &report);
  EXPECT_EQ(w.settings().local_damping, 0.0);
  EXPECT_LT(report.ek_over_ep_undamped, s.preparation.settle_ek_threshold);
}

}  // namespace
}  // namespace runout

// The renderer: drawn facts checked against numbers worked out independently (a disc's colour
// at its centre, its area against pi r^2), golden frames for every colour mode, camera and
// style (a tolerant comparison; the diff is written on failure), and `runout compare`.
//
// Regenerate the goldens on purpose, after looking at them:
//   RUNOUT_UPDATE_GOLDENS=1 build/tests/test_render --gtest_filter='Golden*'
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "runout/render/colormap.hpp"
#include "runout/render/frame.hpp"
#include "runout/render/gl_renderer.hpp"
#include "runout/render/image.hpp"
#include "runout/setup.hpp"
#include "test_helpers.hpp"

namespace runout {
namespace {

using namespace render;

// ---- drawn facts ----

class DiscFacts : public ::testing::TestWithParam<DiscMethod> {};

TEST_P(DiscFacts, CentrePixelHasTheDiscColourAndAreaIsPiRSquared) {
  GlRenderer gl(200, 160);
  gl.set_method(GetParam());
  DiscBatch discs;
  const Rgba colour{213, 94, 0, 255};
  // One metre is 10 pixels; a disc of radius 4 m is 40 px, centred on pixel (100, 80).
  const View view{0.0, 0.0, 10.0};
  discs.add(10.0, 8.0, 4.0, 0.0, colour);
  DrawStyle style;
  style.background = {255, 255, 255, 0};  // transparent: alpha is the coverage
  const Image img = gl.draw(view, discs, {}, style);
  const Rgba centre = img.at(100, 80);
  EXPECT_EQ(centre, colour);
  double area = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) area += img.at(x, y).a / 255.0;
  const double expected = kPi * 40.0 * 40.0;
  EXPECT_NEAR(area, expected, 0.02 * expected);
  EXPECT_EQ(img.at(100, 80 - 45).a, 0) << "nothing beyond the edge";
  // Up is up: a disc placed higher in the world is higher in the image (smaller row).
  DiscBatch high;
  high.add(10.0, 12.0, 1.0, 0.0, colour);
  const Image img2 = gl.draw(view, high, {}, style);
  EXPECT_EQ(img2.at(100, 40), colour);
  EXPECT_EQ(img2.at(100, 120).a, 0);
}

INSTANTIATE_TEST_SUITE_P(BothMethods, DiscFacts,
                         ::testing::Values(DiscMethod::point_sprites, DiscMethod::quads));

TEST(DiscFacts, SpritesAndQuadsAgree) {
  GlRenderer gl(160, 90);
  DiscBatch discs;
  for (int k = 0; k < 20; ++k) discs.add(1.0 + 0.7 * k, 4.0 + std::sin(k), 0.3 + 0.05 * (k % 4), 0.3 * k, {0, 114, 178, 255});
  const View view{0.0, 0.0, 10.0};
  DrawStyle style;
  style.spokes = true;
  style.outline_px = 1.0;
  gl.set_method(DiscMethod::point_sprites);
  const Image a = gl.draw(view, discs, {{0, 1, 16, 1}}, style);
  gl.set_method(DiscMethod::quads);
  const Image b = gl.draw(view, discs, {{0, 1, 16, 1}}, style);
  CompareOptions tight;
  tight.pixel_threshold = 4;  // the two rasterise the same analytic edge
  tight.max_share = 0.001;
  EXPECT_TRUE(compare_images(a, b, tight).match);
}

TEST(DiscFacts, DiscCentredOutsideTheFrameStillShowsItsEdge) {
  GlRenderer gl(100, 100);
  DiscBatch discs;
  discs.add(-0.5, 5.0, 1.0, 0.0, {0, 0, 0, 255});  // centre 5 px left of the frame, radius 10 px
  const Image img = gl.draw({0.0, 0.0, 10.0}, discs, {}, DrawStyle{});
  EXPECT_EQ(img.at(2, 50), (Rgba{0, 0, 0, 255}));
}

// A renderer that drew a frame before clears and redraws only where the discs were or are
// (when view, walls and style are unchanged): the frames must be the bytes a fresh renderer
// draws, whether the discs moved across the whole frame, left it, or the style changed.
TEST(DiscFacts, AFrameAfterAnotherIsTheFrameDrawnAlone) {
  const View view{0.0, 0.0, 10.0};
  const std::vector<SegmentLine> walls = {{0, 1, 16, 1}, {15, 1, 15, 9}};
  DrawStyle style;
  style.spokes = true;
  auto pile = [](double x0, int n) {
    DiscBatch d;
    for (int k = 0; k < n; ++k) d.add(x0 + 0.45 * (k % 5), 1.5 + 0.45 * (k / 5), 0.2, 0.4 * k, {213, 94, 0, 255});
    return d;
  };
  DrawStyle outlined = style;
  outlined.outline_px = 1.0;
  struct Frame { DiscBatch discs; DrawStyle style; };
  // Left, then far right (the left must be cleared), then one disc partly outside the frame,
  // then none, then an outline (a different style: a whole clear), then the left again.
  const std::vector<Frame> frames = {{pile(1.0, 15), style},  {pile(12.0, 15), style}, {pile(15.9, 3), style},
                                     {DiscBatch{}, style},    {pile(6.0, 10), outlined}, {pile(1.0, 15), outlined}};
  GlRenderer reused(160, 90);
  for (std::size_t f = 0; f < frames.size(); ++f) {
    const Image after = reused.draw(view, frames[f].discs, walls, frames[f].style);
    GlRenderer fresh(160, 90);
    const Image& alone = fresh.draw(view, frames[f].discs, walls, frames[f].style);
    EXPECT_TRUE(after.rgba == alone.rgba) << "frame " << f;
  }
}

// Text and rectangles blend in integers; the bytes must be those of the blend in double.
TEST(Blend, CoverageInIntegersEqualsTheBlendInDouble) {
  Image a(256, 256), b(256, 256);
  for (int y = 0; y < 256; ++y)
    for (int x = 0; x < 256; ++x) a.set(x, y, {std::uint8_t(x), std::uint8_t(y), std::uint8_t(x ^ y), std::uint8_t(255 - x)});
  b = a;
  for (const Rgba c : {Rgba{30, 30, 30, 255}, Rgba{255, 255, 255, 210}, Rgba{213, 94, 0, 1}, Rgba{0, 114, 178, 128}})
    for (int coverage = 1; coverage < 256; coverage += 3) {
      for (int y = 0; y < 256; y += 5)
        for (int x = 0; x < 256; ++x) {
          a.blend(x, y, c, coverage / 255.0);
          b.blend_coverage(x, y, c, coverage);
        }
      ASSERT_TRUE(a.rgba == b.rgba) << "colour alpha " << int(c.a) << ", coverage " << coverage;
    }
}

// The PNG writer filters rows in chunks and deflates them with igzip, which writes the zlib
// wrapper itself; libpng's reader (which inflates with zlib and checks the stream's Adler-32)
// must give back every pixel, for one row and many, odd widths, with and without alpha.
TEST(Png, EncodedFramesDecodeToTheSamePixels) {
  std::uint32_t state = 12345;
  auto next = [&] { state = state * 1664525u + 1013904223u; return static_cast<std::uint8_t>(state >> 24); };
  const auto dir = std::filesystem::temp_directory_path() / "runout_png_strips";
  std::filesystem::create_directories(dir);
  for (auto [w, h] : {std::pair{1, 1}, {7, 63}, {300, 64}, {301, 257}, {1280, 720}}) {
    for (bool alpha : {false, true}) {
      Image img(w, h, {255, 255, 255, 255});
      // Noise in the left third (literals), flat blocks elsewhere (runs), so the stream holds
      // both kinds of DEFLATE block.
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
          if (3 * x < w) img.set(x, y, {next(), next(), next(), alpha ? next() : std::uint8_t{255}});
          else if ((x / 16 + y / 16) % 2) img.set(x, y, {0, 114, 178, alpha ? std::uint8_t{128} : std::uint8_t{255}});
      const std::string path = (dir / "strips.png").string();
      write_png(path, img, alpha);
      const Image back = read_png(path);
      ASSERT_EQ(back.width, w);
      ASSERT_EQ(back.height, h);
      long wrong = 0;
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
          Rgba e = img.at(x, y);
          if (!alpha) e.a = 255;
          wrong += !(back.at(x, y) == e);
        }
      EXPECT_EQ(wrong, 0) << w << "x" << h << (alpha ? " RGBA" : " RGB");
    }
  }
  std::filesystem::remove_all(dir);
}

TEST(Compare, CatchesAnAlteredFrameAndToleratesEdges) {
  GlRenderer gl(160, 90);
  DiscBatch discs;
  discs.add(8.0, 4.5, 3.0, 0.0, {0, 114, 178, 255});
  const Image a = gl.draw({0.0, 0.0, 10.0}, discs, {}, DrawStyle{});
  Image altered = a;
  altered.fill_rect(70, 40, 76, 46, {255, 0, 0, 255});  // 36 pixels: 0.25 % of the frame
  const Comparison bad = compare_images(a, altered);
  EXPECT_FALSE(bad.match);
  EXPECT_EQ(bad.differing_pixels, 36);
  EXPECT_EQ(bad.diff.at(72, 42), (Rgba{220, 0, 0, 255}));
  // The same disc moved by a tenth of a pixel changes only anti-aliased edge pixels, slightly.
  DiscBatch moved;
  moved.add(8.01, 4.5, 3.0, 0.0, {0, 114, 178, 255});
  const Image b = gl.draw({0.0, 0.0, 10.0}, moved, {}, DrawStyle{});
  EXPECT_TRUE(compare_images(a, b).match);
  EXPECT_FALSE(compare_images(a, Image(100, 90)).same_size);
}

TEST(Compare, CommandLineExitCodes) {
  const auto dir = std::filesystem::temp_directory_path() / "runout_compare_test";
  std::filesystem::create_directories(dir);
  Image a(64, 48, {255, 255, 255, 255});
  a.fill_rect(10, 10, 30, 30, {0, 114, 178, 255});
  Image b = a;
  b.fill_rect(40, 20, 50, 30, {213, 94, 0, 255});
  write_png((dir / "a.png").string(), a);
  write_png((dir / "b.png").string(), b);
  const std::string bin = RUNOUT_BINARY;
  auto run = [&](const std::string& args) {
    const int status = std::system((bin + " compare " + args + " > /dev/null 2>&1").c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  };
  EXPECT_EQ(run((dir / "a.png").string() + " " + (dir / "a.png").string()), 0);
  EXPECT_EQ(run((dir / "a.png").string() + " " + (dir / "b.png").string() + " --diff " + (dir / "d.png").string()), 1);
  EXPECT_TRUE(std::filesystem::exists(dir / "d.png"));
  EXPECT_EQ(run((dir / "a.png").string() + " " + (dir / "missing.png").string()), 2);
  std::filesystem::remove_all(dir);
}

// ---- cameras ----

// A box like the avalanche's: a 45 degree incline from (-10, 10) to the foot at (0, 0), a floor
// to x = 30, and a back wall and an end wall 60 m tall; a row of eleven touching discs of
// diameter 1 on the floor from x = 0 to 11. The region the mass can reach is the bed, 40 m
// across and 10 m up (the incline's top); the walls rise six times higher.
struct TallWallScene {
  SceneDef scene;
  SceneSetup setup;
  std::optional<World> world;
  TallWallScene() {
    scene.species = {{"disc", 1.0, 0.0, 1.0}};
    scene.walls = {{"bed", {{-10.0, 10.0}, {0.0, 0.0}, {30.0, 0.0}}, true},
                   {"back", {{-10.0, 70.0}, {-10.0, 10.0}}, false},
                   {"end", {{30.0, 0.0}, {30.0, 60.0}}, false}};
    for (int k = 0; k < 11; ++k) scene.particles.push_back(testing::disc(0.5 + k, 0.5, 1.0));
    setup = derive_setup(scene);
    world.emplace(build_explicit_world(scene, setup, 1));
  }
};

FrameOptions bare_frame(CameraMode camera, int width, int height) {
  FrameOptions o;
  o.width = width;
  o.height = height;
  o.camera = camera;
  o.overlays = false;  // no band at the top: the margins are 1.5 % of the width, 10 px at 640
  return o;
}

TEST(Cameras, WholeFitsTheBedAndThePileNotTheWallTops) {
  static TallWallScene g;
  FrameMaker maker(bare_frame(CameraMode::whole, 640, 360), g.scene, g.setup, &*g.world);
  // 40 m across 640 - 2 x 10 px: 15.5 px/m (fitting the 70 m tall walls into 340 px gave 4.9).
  EXPECT_DOUBLE_EQ(maker.view().scale, 15.5);
  const Image img = maker.make(*g.world, 0.0);
  // The back wall (x = -10 m, column 10) rises from the incline's top (y = 10 m) and stops a
  // margin (10 px) above it: drawn 5 px above the top, sky 20 px above.
  const double top_row = 180.0 - 5.0 * 15.5;  // y = 10 m: the box's centre (y = 5) is row 180
  EXPECT_EQ(img.at(10, static_cast<int>(top_row) - 20), (Rgba{255, 255, 255, 255}));
  EXPECT_NE(img.at(10, static_cast<int>(top_row) - 5), (Rgba{255, 255, 255, 255}));
}

TEST(Cameras, HeightZeroFollowsTheCamerasAspect) {
  static TallWallScene g;
  // whole: 10 m of 40 m at 15.5 px/m is 155 px, plus two 10 px margins: 175, rounded up to even.
  EXPECT_EQ(FrameMaker(bare_frame(CameraMode::whole, 640, 0), g.scene, g.setup, &*g.world).options().height, 176);
  // deposit: the row, 11 m long and 1.5 m tall (half a D below it for the bed): 620 / 11 px/m,
  // 84.5 px + 20.
  EXPECT_EQ(FrameMaker(bare_frame(CameraMode::deposit, 640, 0), g.scene, g.setup, &*g.world).options().height, 106);
  // window: its own aspect, 20 m x 5 m; front: 16:9.
  FrameOptions win = bare_frame(CameraMode::window, 640, 0);
  win.window = {0.0, 0.0, 20.0, 5.0};
  EXPECT_EQ(FrameMaker(win, g.scene, g.setup, &*g.world).options().height, 160);
  EXPECT_EQ(FrameMaker(bare_frame(CameraMode::front, 640, 0), g.scene, g.setup, &*g.world).options().height, 360);
  // With overlays the band on top adds to the height, and no World at all is refused.
  FrameOptions with_band = bare_frame(CameraMode::whole, 640, 0);
  with_band.overlays = true;
  EXPECT_GT(FrameMaker(with_band, g.scene, g.setup, &*g.world).options().height, 176 + 20);
  EXPECT_THROW(FrameMaker(bare_frame(CameraMode::whole, 640, 0), g.scene, g.setup), std::invalid_argument);
}

TEST(Cameras, DepositCoversTheBodyWithTheOverlaysAboveIt) {
  static TallWallScene g;
  FrameOptions o = bare_frame(CameraMode::deposit, 1280, 0);
  o.overlays = true;
  FrameMaker maker(o, g.scene, g.setup, &*g.world);
  const Image img = maker.make(*g.world, 0.0);
  // The row spans the width between the margins (19 px each at 1280): its first and last
  // discs' centres are at 0.5 and 10.5 m of 11 m.
  const double scale = maker.view().scale;
  EXPECT_NEAR(scale, (1280 - 2 * 19) / 11.0, 1e-9);
  const int H = maker.options().height;
  const double top_world = maker.view().y0 + H / scale;  // y of the frame's top edge
  const int row = static_cast<int>((top_world - 0.5) * scale);
  for (int k : {0, 10}) {
    const int col = static_cast<int>((0.5 + k - maker.view().x0) * scale);
    EXPECT_EQ(img.at(col, row), palette::kLarge) << "disc " << k;
  }
  // The frame is the band, two margins and the 1.5 m box; the box starts a margin below the
  // band, so no panel covers a disc.
  const double band = H - 2 * 19 - 1.5 * scale;
  EXPECT_GT(band, 40);
  EXPECT_NEAR((top_world - 1.0) * scale, band + 19, 1.0);
}

// ---- golden frames ----

// A small deterministic scene: an incline and a floor, discs of two species with set spins,
// speeds and rotation angles (no simulation: the picture depends on drawing only).
struct GoldenScene {
  SceneDef scene;
  SceneSetup setup;
  std::optional<World> world;
  GoldenScene() {
    scene.species = {{"large", 1.0, 0.0, 0.5}, {"small", 0.4, 0.0, 0.5}};
    scene.walls = {{"bed", {{-12.0, 12.0 * std::tan(0.5236)}, {0.0, 0.0}, {14.0, 0.0}}, true},
                   {"end", {{14.0, 0.0}, {14.0, 3.0}}, false}};
    int k = 0;
    for (int row = 0; row < 3; ++row)
      for (int col = 0; col < 9; ++col, ++k) {
        const bool large = (row + col) % 3 == 0;
        const double d = large ? 1.0 : 0.4;
        const double x = 1.0 + col * 1.05 + (row % 2) * 0.5, y = 0.5 * d + row * 0.8 + (large ? 0.0 : 0.05);
        ParticleDef p = testing::disc(x, y, d, large ? 0 : 1, 0.4 * col - 1.0, 0.1 * row, (col - 4) * 9.0);
        scene.particles.push_back(p);
      }
    scene.particles.push_back(testing::disc(0.0, 0.2, 0.4, 1));  // small, under nothing
    scene.particles.push_back(testing::disc(-6.0, 6.0 * std::tan(0.5236) + 0.6, 1.0, 0, 2.0, -1.0, -3.0));
    setup = derive_setup(scene);
    World w = build_explicit_world(scene, setup, 1);
    Particles p = w.particles();
    for (std::size_t i = 0; i < p.size(); ++i) p.angle[i] = 0.7 * i;
    world.emplace(std::move(p), w.segments(), w.table(), w.settings());
  }
};

struct GoldenCase {
  const char* name;
  ColorMode color;
  CameraMode camera;
  bool spokes, outlines, overlays;
};

void check_golden(const GoldenCase& c) {
  static GoldenScene g;
  FrameOptions o;
  o.width = 320;
  o.height = 180;
  o.color = c.color;
  o.camera = c.camera;
  o.window = {2.0, -0.5, 8.0, 3.0};
  o.front_width = 8.0;
  o.spokes = c.spokes;
  o.outlines = c.outlines;
  o.overlays = c.overlays;
  o.speed_limit = 4.0;
  FrameMaker maker(o, g.scene, g.setup);
  const Image img = maker.make(*g.world, 12.5);
  const std::string golden = std::string(RUNOUT_SOURCE_DIR) + "/tests/golden/" + c.name + ".png";
  if (const char* u = std::getenv("RUNOUT_UPDATE_GOLDENS"); u && std::string(u) == "1") {
    write_png(golden, img);
    GTEST_SKIP() << "wrote " << golden;
  }
  ASSERT_TRUE(std::filesystem::exists(golden)) << golden << " is missing; see the header of this file";
  // Tolerance: a pixel differs if a channel is off by more than 24 of 255, and up to 0.2 % of
  // the pixels may differ (anti-aliased edges after a Mesa or FreeType update).
  const Comparison cmp = compare_images(read_png(golden), img);
  if (!cmp.match) {
    const auto out = std::filesystem::current_path() / "render_failures";
    std::filesystem::create_directories(out);
    const std::string actual = (out / (std::string(c.name) + "-actual.png")).string();
    const std::string diff = (out / (std::string(c.name) + "-diff.png")).string();
    write_png(actual, img);
    if (cmp.same_size) write_png(diff, cmp.diff);
    FAIL() << c.name << ": " << cmp.differing_pixels << " pixels differ (" << 100 * cmp.share
           << " %), rms " << cmp.rms << "; actual " << actual << ", diff " << diff;
  }
}

class Golden : public ::testing::TestWithParam<GoldenCase> {};
TEST_P(Golden, MatchesTheStoredFrame) { check_golden(GetParam()); }

INSTANTIATE_TEST_SUITE_P(
    Frames, Golden,
    ::testing::Values(GoldenCase{"species_whole", ColorMode::species, CameraMode::whole, false, false, true},
                      GoldenCase{"spin_window_spokes", ColorMode::spin, CameraMode::window, true, true, true},
                      GoldenCase{"layer_deposit", ColorMode::layer, CameraMode::deposit, false, false, true},
                      GoldenCase{"speed_front", ColorMode::speed, CameraMode::front, false, true, true},
                      GoldenCase{"species_window_plain", ColorMode::species, CameraMode::window, false, false, false}),
    [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace runout

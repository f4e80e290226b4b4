// From a World to a finished frame: colours by species, spin, basal layer or speed; a camera;
// walls; the colour bar or legend, the t* stamp and a scale bar in units of D (SPEC §8).
#pragma once

#include <array>
#include <limits>
#include <memory>
#include <optional>
#include <string>

#include "runout/render/canvas.hpp"
#include "runout/render/gl_renderer.hpp"
#include "runout/render/text.hpp"
#include "runout/setup.hpp"
#include "runout/world.hpp"

namespace runout::render {

enum class ColorMode { species, spin, layer, speed };
enum class CameraMode { whole, front, deposit, window };

ColorMode parse_color_mode(const std::string& s);    // throws std::invalid_argument
CameraMode parse_camera_mode(const std::string& s);
const char* to_string(ColorMode m);
const char* to_string(CameraMode m);

struct FrameOptions {
  int width = 1280, height = 720;  // height 0: from the camera's aspect (FrameMaker resolves it)
  ColorMode color = ColorMode::species;
  CameraMode camera = CameraMode::whole;
  std::array<double, 4> window{0, 0, 0, 0};  // camera window: x0, y0, x1, y1 in metres
  double front_width = 50.0;   // front camera: window width in large diameters D
  bool spokes = false;
  bool outlines = false;
  bool transparent = false;    // PNG with alpha; videos ignore it
  bool overlays = true;        // legend or colour bar, t* stamp, scale bar
  double spin_limit = 10.0;    // |omega sqrt(d/g)| at the ends of the spin map (fixed per movie)
  double speed_limit = 0.0;    // |v| / sqrt(g d) at the top of viridis; 0: free-fall speed from
                               // the highest disc of the first frame (fixed per movie)
  DiscMethod method = DiscMethod::point_sprites;
};

// Everything one frame shows, taken from the World on the simulation thread; drawing it needs
// no World, so it can happen on another thread while the simulation goes on.
struct FramePlan {
  View view;
  DiscBatch discs;
  std::vector<SegmentLine> walls;
  double t_star = 0;
};

// Owns an OpenGL context and a font; keeps the camera's state between frames so every frame
// of one FrameMaker has the same scale (and the front camera moves smoothly).
class FrameMaker {
 public:
  // `first`: the World of the first frame. A height of 0 needs it: the frame is then as tall as
  // the camera's view of that World asks for (whole, deposit: their extent; window: its aspect;
  // front: 16:9), rounded up to even, 16..8192; options().height gives it.
  FrameMaker(const FrameOptions& options, const SceneDef& scene, const SceneSetup& setup,
             const World* first = nullptr);
  // plan() reads the World and moves the camera; draw() makes the picture (any one thread at a
  // time) in the maker's own buffer, valid until its next draw. make() is both.
  FramePlan plan(const World& world, double t_star);
  Image& draw(const FramePlan& plan);
  Image& make(const World& world, double t_star) { return draw(plan(world, t_star)); }
  // The same picture as a PDF (cairo) or SVG file's bytes: the same discs, colours, walls and
  // overlays, drawn as shapes and text (vector.cpp).
  std::string draw_vector(const FramePlan& plan, PictureFormat format);
  std::string make_vector(const World& world, double t_star, PictureFormat format) {
    return draw_vector(plan(world, t_star), format);
  }
  const FrameOptions& options() const { return options_; }
  // What the legend says (species or basal-layer mode): each entry's colour and label; the same
  // entries whether overlays are drawn or a figure draws its own legend (runout plot).
  std::vector<std::pair<Rgba, std::string>> legend_entries() const;
  const View& view() const { return view_; }

 private:
  void update_camera(const World& world, double t_star);
  void decide_whole(const World& world);  // the whole camera's one window, and wall_top_
  // The whole and deposit cameras' world box (m) for this World; the other cameras have none.
  std::optional<std::array<double, 4>> content_box(const World& world) const;
  // A box fitted below the overlays' band (they never cover the pile), with a margin.
  View fit_content(const std::array<double, 4>& box);
  View place_content(const std::array<double, 4>& box, double scale);  // centred below the band
  int frame_height_for(const World& world);  // the height 0 resolves to
  // Where the overlays go, in frame pixels; `band` is the height of the strip they take at the
  // top (0 without overlays). draw_overlays() draws exactly this.
  struct OverlayLayout {
    int fs = 10, pad = 5, line = 1, asc = 8;
    int band = 0;
  };
  OverlayLayout overlay_layout();
  void colour_discs(const World& world);
  DrawStyle style(const FramePlan& plan) const;
  void draw_overlays(Canvas& canvas, const FramePlan& plan);
  std::string species_label(int species) const;

  FrameOptions options_;
  const SceneDef& scene_;
  const SceneSetup& setup_;
  TextRenderer text_;
  std::optional<GlRenderer> gl_;  // made once the frame size is known
  DiscBatch discs_;
  View view_;
  bool have_view_ = false;
  double last_t_star_ = 0;
  double wall_top_ = std::numeric_limits<double>::infinity();  // walls are cut at this y (m)
  double speed_limit_ = 0;
  std::vector<Rgba> species_colour_;  // species mode, per species
};

// World window [x0, x1] x [y0, y1] fitted into a width x height frame with a margin (share of
// the frame), centred.
View fit_view(double x0, double y0, double x1, double y1, int width, int height, double margin);

}  // namespace runout::render

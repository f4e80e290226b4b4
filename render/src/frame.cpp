// FrameMaker's set-up (the species' colours, the frame size), the discs' colours, the plan of a
// frame and its drawing, in OpenGL or as a vector file. The cameras are in frame_camera.cpp, the
// overlays in frame_overlays.cpp.
#include "runout/render/frame.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "runout/measure.hpp"
#include "runout/render/colormap.hpp"
#include "runout/render/vector.hpp"

namespace runout::render {

ColorMode parse_color_mode(const std::string& s) {
  if (s == "species") return ColorMode::species;
  if (s == "spin") return ColorMode::spin;
  if (s == "layer") return ColorMode::layer;
  if (s == "speed") return ColorMode::speed;
  throw std::invalid_argument("colour mode \"" + s + "\" is not one of species, spin, layer, speed");
}
CameraMode parse_camera_mode(const std::string& s) {
  if (s == "whole") return CameraMode::whole;
  if (s == "front") return CameraMode::front;
  if (s == "deposit") return CameraMode::deposit;
  if (s == "window") return CameraMode::window;
  throw std::invalid_argument("camera \"" + s + "\" is not one of whole, front, deposit, window");
}
const char* to_string(ColorMode m) {
  switch (m) {
    case ColorMode::species: return "species";
    case ColorMode::spin: return "spin";
    case ColorMode::layer: return "layer";
    case ColorMode::speed: return "speed";
  }
  return "?";
}
const char* to_string(CameraMode m) {
  switch (m) {
    case CameraMode::whole: return "whole";
    case CameraMode::front: return "front";
    case CameraMode::deposit: return "deposit";
    case CameraMode::window: return "window";
  }
  return "?";
}

FrameMaker::FrameMaker(const FrameOptions& options, const SceneDef& scene, const SceneSetup& setup,
                       const World* first)
    : options_(options), scene_(scene), setup_(setup) {
  // Two or three species: the Okabe–Ito pair (and green for a third); a polydisperse pile's
  // classes: viridis by size, dark for the smallest, stopping short of its pale yellow.
  const int n = static_cast<int>(scene.species.size());
  std::vector<int> present;
  for (int s = 0; s < n; ++s)
    if (setup.counts[s] > 0) present.push_back(s);
  std::sort(present.begin(), present.end(),
            [&](int a, int b) { return scene.species[a].diameter < scene.species[b].diameter; });
  species_colour_.assign(n, palette::kOther);
  for (int s = 0; s < n; ++s)
    if (s == setup.largest_species) species_colour_[s] = palette::kLarge;
    else if (s == setup.roles.small) species_colour_[s] = palette::kSmall;
  if (present.size() > 3)
    for (std::size_t r = 0; r < present.size(); ++r)
      species_colour_[present[r]] = viridis(0.85 * static_cast<double>(r) / (present.size() - 1));
  if (options_.height == 0) {
    if (!first) throw std::invalid_argument("a frame height of 0 needs the first frame's World to size it");
    options_.height = frame_height_for(*first);
  }
  gl_.emplace(options_.width, options_.height);
  gl_->set_method(options_.method);
  // The whole camera is decided on the state the pictures start from, so snapshots that begin
  // later (t* = 20, 60) share the movie's window and the height 0 was sized for.
  if (first && options_.camera == CameraMode::whole) decide_whole(*first);
}

void FrameMaker::colour_discs(const World& world) {
  const auto& p = world.particles();
  discs_.clear();
  std::vector<char> layer;
  if (options_.color == ColorMode::layer)
    layer = basal_layer(p, world.segments(), setup_.roles, setup_.large_diameter, 0.7).member;
  if (options_.color == ColorMode::speed && speed_limit_ <= 0) {
    // Free fall from the highest disc to the floor, in sqrt(g d): fixed for the movie.
    double top = 0;
    for (std::size_t k = 0; k < p.size(); ++k) top = std::max(top, p.y[k]);
    speed_limit_ = options_.speed_limit > 0 ? options_.speed_limit
                                            : std::max(1.0, std::sqrt(2.0 * top / setup_.unit_length));
  }
  const double sqrt_gd = std::sqrt(scene_.integration.gravity * setup_.unit_length);
  for (std::size_t k = 0; k < p.size(); ++k) {
    const int s = p.species[k];
    Rgba c;
    switch (options_.color) {
      case ColorMode::species:
        c = species_colour_[s];
        break;
      case ColorMode::spin:
        c = diverging(p.omega[k] * setup_.unit_time / options_.spin_limit);
        break;
      case ColorMode::speed:
        c = viridis(std::hypot(p.vx[k], p.vy[k]) / sqrt_gd / speed_limit_);
        break;
      case ColorMode::layer:
        // The layer is the smallest class (measure.hpp); every larger disc is the muted blue.
        c = layer[k] ? palette::kSmall : (s == setup_.roles.small ? palette::kMutedSmall : palette::kMutedLarge);
        break;
    }
    discs_.add(p.x[k], p.y[k], p.radius[k], p.angle[k], c);
  }
}

namespace {

// Overlays on a PNG: blended on the CPU onto the OpenGL frame, text through FreeType.
class ImageCanvas : public Canvas {
 public:
  ImageCanvas(Image& image, TextRenderer& text) : image_(image), text_(text) {}
  void rect(int x0, int y0, int x1, int y1, Rgba c) override { image_.fill_rect(x0, y0, x1, y1, c); }
  void disc(double cx, double cy, double r, Rgba c) override {
    // Coverage from the distance to the edge, as the disc shader has it.
    for (int py = static_cast<int>(std::floor(cy - r - 1)); py <= static_cast<int>(std::ceil(cy + r + 1)); ++py)
      for (int px = static_cast<int>(std::floor(cx - r - 1)); px <= static_cast<int>(std::ceil(cx + r + 1)); ++px)
        if (px >= 0 && py >= 0 && px < image_.width && py < image_.height)
          image_.blend(px, py, c, std::clamp(r - std::hypot(px + 0.5 - cx, py + 0.5 - cy) + 0.5, 0.0, 1.0));
  }
  void text(int x, int y, std::string_view utf8, int pixel_size, Rgba c) override {
    text_.draw(image_, x, y, utf8, pixel_size, c);
  }

 private:
  Image& image_;
  TextRenderer& text_;
};

}  // namespace

FramePlan FrameMaker::plan(const World& world, double t_star) {
  update_camera(world, t_star);
  colour_discs(world);
  FramePlan plan;
  plan.view = view_;
  plan.discs = std::move(discs_);  // colour_discs() refills it next frame
  for (const auto& s : world.segments()) {
    if (!s.active) continue;
    SegmentLine w{s.a.x(), s.a.y(), s.b.x(), s.b.y()};
    if (w.ay > wall_top_ && w.by > wall_top_) continue;  // wholly above: not drawn
    if (w.ay > wall_top_ || w.by > wall_top_) {  // cut where it crosses the top
      const double t = (wall_top_ - w.ay) / (w.by - w.ay);
      const double cx = w.ax + t * (w.bx - w.ax);
      if (w.ay > wall_top_) { w.ax = cx; w.ay = wall_top_; } else { w.bx = cx; w.by = wall_top_; }
    }
    plan.walls.push_back(w);
  }
  plan.t_star = t_star;
  last_t_star_ = t_star;
  return plan;
}

DrawStyle FrameMaker::style(const FramePlan& plan) const {
  DrawStyle style;
  if (options_.transparent) style.background.a = 0;
  // Outlines and spokes scale with the drawn size of a small disc.
  const double small_px = setup_.unit_length * 0.5 * plan.view.scale;
  style.outline_px = options_.outlines ? std::clamp(0.12 * small_px, 0.6, 3.0) : 0.0;
  style.spokes = options_.spokes;
  style.wall_half_width_px = std::max(1.0, options_.height / 480.0);
  return style;
}

Image& FrameMaker::draw(const FramePlan& plan) {
  Image& img = gl_->draw(plan.view, plan.discs, plan.walls, style(plan));
  if (options_.overlays) {
    ImageCanvas canvas(img, text_);
    draw_overlays(canvas, plan);
  }
  return img;
}

std::string FrameMaker::draw_vector(const FramePlan& plan, PictureFormat format) {
  return encode_vector(format, options_.width, options_.height, plan, style(plan), [&](Canvas& canvas) {
    if (options_.overlays) draw_overlays(canvas, plan);
  });
}

}  // namespace runout::render

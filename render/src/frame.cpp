#include "runout/render/frame.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
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

View fit_view(double x0, double y0, double x1, double y1, int width, int height, double margin) {
  const double w = std::max(x1 - x0, 1e-9), h = std::max(y1 - y0, 1e-9);
  const double usable = 1.0 - 2.0 * margin;
  const double scale = std::min(width * usable / w, height * usable / h);
  const double cx = 0.5 * (x0 + x1), cy = 0.5 * (y0 + y1);
  return {cx - 0.5 * width / scale, cy - 0.5 * height / scale, scale};
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

namespace {

struct Box {
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  void add(double x, double y) { x0 = std::min(x0, x); y0 = std::min(y0, y); x1 = std::max(x1, x); y1 = std::max(y1, y); }
  bool empty() const { return x1 < x0; }
};

}  // namespace

std::optional<std::array<double, 4>> FrameMaker::content_box(const World& world) const {
  const auto& p = world.particles();
  const double D = setup_.large_diameter;
  Box b;
  switch (options_.camera) {
    case CameraMode::whole: {
      // The region the mass can reach: across, every wall's ends (the back wall to the end
      // wall); up, the bed (the incline's top) and the discs, not the walls' tops: back and end
      // walls rise 30-60 D above a pile a few D deep, and fitting them left the pile in the
      // bottom fifth of an empty box. Walls above the box run off the top of the frame.
      Box bed;
      for (const auto& s : world.segments())
        if (s.active) {
          b.add(s.a.x(), s.a.y());
          b.add(s.b.x(), s.b.y());
          if (s.bed) { bed.add(s.a.x(), s.a.y()); bed.add(s.b.x(), s.b.y()); }
        }
      if (!bed.empty()) { b.y0 = bed.y0; b.y1 = bed.y1; }  // no bed (plates only): all walls
      for (std::size_t k = 0; k < p.size(); ++k) {
        b.add(p.x[k] - p.radius[k], p.y[k] - p.radius[k]);
        b.add(p.x[k] + p.radius[k], p.y[k] + p.radius[k]);
      }
      break;
    }
    case CameraMode::deposit: {
      // The body of the mass (its scattered ends left out, as for L1) and half a D under it, so
      // the bed shows.
      const auto [start, end] = deposit_extent(p, D, 0.0, 1);  // lone discs beyond a gap left out
      for (std::size_t k = 0; k < p.size(); ++k)
        if (p.x[k] >= start && p.x[k] <= end) {
          b.add(p.x[k] - p.radius[k], p.y[k] - p.radius[k] - 0.5 * D);
          b.add(p.x[k] + p.radius[k], p.y[k] + p.radius[k]);
        }
      break;
    }
    case CameraMode::front:
    case CameraMode::window:
      return std::nullopt;
  }
  if (b.empty()) b = {-1, -1, 1, 1};
  return std::array<double, 4>{b.x0, b.y0, b.x1, b.y1};
}

namespace {
// The margin around a fitted box, in pixels: 1.5 % of the width, so a strip's margins are as
// thin as a 16:9 frame's side margins.
int content_margin_px(int width) { return std::max(4, static_cast<int>(std::lround(0.015 * width))); }
}  // namespace

View FrameMaker::fit_content(const std::array<double, 4>& box) {
  const int W = options_.width, H = options_.height, m = content_margin_px(W);
  const int band = overlay_layout().band;
  const double w = std::max(box[2] - box[0], 1e-9), h = std::max(box[3] - box[1], 1e-9);
  const double usable_w = std::max(W - 2.0 * m, 1.0), usable_h = std::max(H - band - 2.0 * m, 1.0);
  return place_content(box, std::min(usable_w / w, usable_h / h));
}

View FrameMaker::place_content(const std::array<double, 4>& box, double scale) {
  // The box's centre at the centre of the frame below the band (image rows run down, world y up).
  const int band = overlay_layout().band;
  const double cx = 0.5 * (box[0] + box[2]), cy = 0.5 * (box[1] + box[3]);
  return {cx - 0.5 * options_.width / scale, cy - 0.5 * (options_.height - band) / scale, scale};
}

int FrameMaker::frame_height_for(const World& world) {
  const int W = options_.width;
  double height = 9.0 / 16.0 * W;  // front: a 16:9 window, as wide as --front-width
  if (const auto box = content_box(world)) {
    // A wide box gives a strip; a tall one (a pile seen by the deposit camera) at most a square.
    const double w = std::max((*box)[2] - (*box)[0], 1e-9), h = std::max((*box)[3] - (*box)[1], 1e-9);
    const int m = content_margin_px(W);
    height = overlay_layout().band + 2.0 * m + h * (W - 2.0 * m) / w;
  } else if (options_.camera == CameraMode::window) {
    const auto& win = options_.window;
    height = W * (win[3] - win[1]) / (win[2] - win[0]);
  }
  if (content_box(world)) height = std::min<double>(height, W);
  const int even = 2 * static_cast<int>(std::ceil(height / 2.0 - 1e-9));  // H.264 needs even sizes
  return std::clamp(even, 16, 8192);
}

void FrameMaker::decide_whole(const World& world) {
  const auto box = *content_box(world);
  view_ = fit_content(box);
  // The back wall, the gate and the end wall end a margin above the pile instead of running up
  // into the overlays' band.
  wall_top_ = box[3] + content_margin_px(options_.width) / view_.scale;
  have_view_ = true;
}

void FrameMaker::update_camera(const World& world, double t_star) {
  const auto& p = world.particles();
  const int W = options_.width, H = options_.height;
  const double D = setup_.large_diameter;
  switch (options_.camera) {
    case CameraMode::whole:
      // Decided once, on the first state (the pile and the geometry): one scale and one window
      // for the whole movie. The pile does not rise above its start, and the end wall stops it.
      if (have_view_) return;
      decide_whole(world);
      break;
    case CameraMode::window: {
      const auto& w = options_.window;
      view_ = fit_view(w[0], w[1], w[2], w[3], W, H, 0.0);
      break;
    }
    case CameraMode::front: {
      // A fixed-size window that follows the front: the 98th percentile of x (the few discs
      // ahead of the mass do not drag it), placed at three quarters of the width; vertically
      // on the discs in view, but never with their lowest edge above a fifth of the height (a
      // thin flow on the floor sits low, not mid-frame). Smoothed with a time constant of 3 t*.
      const double scale = W / (options_.front_width * D);
      const double half_w = 0.5 * W / scale, half_h = 0.5 * H / scale;
      double cx = view_.x0 + half_w, cy = view_.y0 + half_h;
      if (p.size() > 0) {
        std::vector<double> xs(p.x);
        const std::size_t at = static_cast<std::size_t>(0.98 * (xs.size() - 1));
        std::nth_element(xs.begin(), xs.begin() + at, xs.end());
        const double target_x = xs[at] - 0.5 * half_w;
        std::vector<double> ys, lows;
        for (std::size_t k = 0; k < p.size(); ++k)
          if (std::abs(p.x[k] - target_x) < half_w) { ys.push_back(p.y[k]); lows.push_back(p.y[k] - p.radius[k]); }
        double target_y = cy;
        if (!ys.empty()) {
          std::nth_element(ys.begin(), ys.begin() + ys.size() / 2, ys.end());
          const double low = *std::min_element(lows.begin(), lows.end());
          target_y = std::max(ys[ys.size() / 2], low + 0.6 * half_h);
        }
        const double follow = have_view_ ? 1.0 - std::exp(-std::max(t_star - last_t_star_, 0.0) / 3.0) : 1.0;
        cx += follow * (target_x - cx);
        cy += follow * (target_y - cy);
        if (!have_view_) { cx = target_x; cy = target_y; }
      }
      view_ = {cx - half_w, cy - half_h, scale};
      break;
    }
    case CameraMode::deposit: {
      // Fits the body of the mass; the scale is set by the first frame and kept, the window
      // recentred on the body.
      const auto box = *content_box(world);
      view_ = have_view_ ? place_content(box, view_.scale) : fit_content(box);
      break;
    }
  }
  have_view_ = true;
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

// 1, 2, 5 times a power of ten, the largest not above `x`.
double nice_below(double x) {
  const double p = std::pow(10.0, std::floor(std::log10(x)));
  for (double m : {5.0, 2.0, 1.0})
    if (m * p <= x) return m * p;
  return p;
}

// Labels people read: whole numbers as such, the rest to three significant digits
// (d = 0.333 m, not 0.333333 m).
std::string format_number(double v) {
  char buf[32];
  if (std::abs(v - std::round(v)) < 1e-9) std::snprintf(buf, sizeof buf, "%.0f", v);
  else std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

}  // namespace

std::string FrameMaker::species_label(int s) const {
  const SpeciesDef& sp = scene_.species[s];
  char buf[160];
  if (sp.distribution != SizeDistribution::spread)
    std::snprintf(buf, sizeof buf, "%s, d = %.3g\u2013%.3g m", sp.name.c_str(), sp.min_diameter, sp.max_diameter);
  else
    std::snprintf(buf, sizeof buf, "%s, %s = %s m", sp.name.c_str(), s == setup_.largest_species ? "D" : "d",
                  format_number(sp.diameter).c_str());
  return buf;
}

std::vector<std::pair<Rgba, std::string>> FrameMaker::legend_entries() const {
  std::vector<std::pair<Rgba, std::string>> entries;
  if (options_.color == ColorMode::layer) {
    const bool many = std::count_if(setup_.counts.begin(), setup_.counts.end(), [](int c) { return c > 0; }) > 2;
    return {{palette::kSmall, "basal layer"}, {palette::kMutedSmall, "other small"},
            {palette::kMutedLarge, many ? "larger classes" : "large"}};
  }
  if (options_.color != ColorMode::species) return entries;
  for (std::size_t s = 0; s < scene_.species.size(); ++s)
    if (setup_.counts[s] > 0) entries.push_back({species_colour_[s], species_label(static_cast<int>(s))});
  return entries;
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

// Every overlay sits in one band across the top: the t* stamp and the scale bar at the left,
// the legend or colour bar at the right. The whole and deposit cameras fit the pile below the
// band, so no panel covers a disc (a strip frame has no empty corner to spare).
FrameMaker::OverlayLayout FrameMaker::overlay_layout() {
  OverlayLayout l;
  // From the width alone, so a frame whose height follows the camera can be sized with it;
  // the same as H / 36 in a 16:9 frame.
  l.fs = std::max(10, static_cast<int>(std::lround(options_.width / 64.0)));
  l.pad = std::max(4, l.fs / 2);
  l.line = std::max(1, l.fs / 9);
  l.asc = text_.ascent(l.fs);
  if (!options_.overlays) return l;
  const int stamp_bottom = l.pad + l.asc + l.fs / 3;
  const int scale_bottom = l.pad / 2 + l.asc + l.fs / 2 + 2 * l.line + l.pad / 2;
  int right_bottom;
  if (options_.color == ColorMode::spin || options_.color == ColorMode::speed)
    right_bottom = l.pad + l.asc + l.fs / 3 + std::max(6, l.fs * 2 / 3) + l.asc + 2 + l.fs / 3;
  else
    right_bottom = l.pad + (l.fs + l.fs / 3) * static_cast<int>(legend_entries().size());
  l.band = std::max({stamp_bottom, scale_bottom, right_bottom}) + l.pad / 2;
  return l;
}

void FrameMaker::draw_overlays(Canvas& canvas, const FramePlan& plan) {
  const double t_star = plan.t_star;
  const int W = options_.width;
  const OverlayLayout l = overlay_layout();
  const int fs = l.fs, pad = l.pad, line = l.line, asc = l.asc;
  const Rgba ink = palette::kInk, panel{255, 255, 255, 210};

  // t* stamp, top left; its panel as wide as the widest stamp, so the scale bar beside it
  // does not move from frame to frame.
  char stamp[64];
  std::snprintf(stamp, sizeof stamp, "t* = %.1f", t_star);
  const int stamp_w = std::max(text_.width(stamp, fs), text_.width("t* = 000.0", fs));
  canvas.rect(pad / 2, pad / 2, pad + stamp_w + pad / 2, pad + asc + fs / 3, panel);
  canvas.text(pad, pad + asc, stamp, fs, ink);

  // Scale bar in units of D, right of the stamp: about an eighth of the width.
  const double D = setup_.large_diameter;
  const double px_per_D = D * plan.view.scale;
  const double n_D = nice_below(std::max(W / 8.0 / px_per_D, 1e-3));
  const int bar = static_cast<int>(std::lround(n_D * px_per_D));
  const std::string label = format_number(n_D) + " D";
  const int bx = pad + stamp_w + 2 * pad, by = pad / 2 + asc + fs / 2 + line;
  canvas.rect(bx - pad / 2, pad / 2, bx + std::max(bar, text_.width(label, fs)) + pad / 2, by + line + pad / 2, panel);
  canvas.rect(bx, by, bx + bar, by + line + 1, ink);
  canvas.rect(bx, by - fs / 3, bx + line + 1, by + line + 1, ink);
  canvas.rect(bx + bar - line - 1, by - fs / 3, bx + bar, by + line + 1, ink);
  canvas.text(bx, by - fs / 3 - line - 1, label, fs, ink);

  // Legend or colour bar, top right.
  if (options_.color == ColorMode::spin || options_.color == ColorMode::speed) {
    const bool spin = options_.color == ColorMode::spin;
    const int bw = std::max(60, W / 5), bh = std::max(6, fs * 2 / 3);
    const int x1 = W - pad, x0 = x1 - bw;
    const std::string title = spin ? "ω √(d/g)" : "|v| / √(g d)";
    const double lo = spin ? -options_.spin_limit : 0.0, hi = spin ? options_.spin_limit : speed_limit_;
    const int y_title = pad + asc, y_bar = y_title + fs / 3, y_labels = y_bar + bh + asc + 2;
    canvas.rect(x0 - pad / 2, pad / 2, W - pad / 2, y_labels + fs / 3, panel);
    canvas.text(x0 + (bw - text_.width(title, fs)) / 2, y_title, title, fs, ink);
    for (int x = 0; x < bw; ++x) {
      const double t = (x + 0.5) / bw;
      const Rgba c = spin ? diverging(2 * t - 1) : viridis(t);
      canvas.rect(x0 + x, y_bar, x0 + x + 1, y_bar + bh, c);
    }
    // End labels inside the bar's span; a true minus sign.
    const std::string l0 = (lo < 0 ? "\u2212" : "") + format_number(std::abs(lo)), l1 = format_number(hi);
    canvas.text(x0, y_labels, l0, fs, ink);
    canvas.text(x1 - text_.width(l1, fs), y_labels, l1, fs, ink);
    if (spin) canvas.text(x0 + bw / 2 - text_.width("0", fs) / 2, y_labels, "0", fs, ink);
  } else {
    const auto entries = legend_entries();
    int widest = 0;
    for (const auto& e : entries) widest = std::max(widest, text_.width(e.second, fs));
    const int row = fs + fs / 3, sw = fs;  // swatch size
    const int x0 = W - pad - widest - sw - pad / 2;
    canvas.rect(x0 - pad / 2, pad / 2, W - pad / 2, pad + row * static_cast<int>(entries.size()), panel);
    for (std::size_t k = 0; k < entries.size(); ++k) {
      const int y = pad + static_cast<int>(k) * row;
      // A small disc as the swatch.
      canvas.disc(x0 + sw / 2.0, y + sw / 2.0, sw * 0.42, entries[k].first);
      canvas.text(x0 + sw + pad / 2, y + asc - (asc - sw) / 2 - 1, entries[k].second, fs, ink);
    }
  }
}

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

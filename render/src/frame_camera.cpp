// The cameras: which part of the world a frame shows, at what scale, and the height a frame of
// height 0 resolves to. Each camera fits its box below the overlays' band (frame_overlays.cpp).
#include "runout/render/frame.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "runout/measure.hpp"

namespace runout::render {

View fit_view(double x0, double y0, double x1, double y1, int width, int height, double margin) {
  const double w = std::max(x1 - x0, 1e-9), h = std::max(y1 - y0, 1e-9);
  const double usable = 1.0 - 2.0 * margin;
  const double scale = std::min(width * usable / w, height * usable / h);
  const double cx = 0.5 * (x0 + x1), cy = 0.5 * (y0 + y1);
  return {cx - 0.5 * width / scale, cy - 0.5 * height / scale, scale};
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
        std::vector<double> xs(p.x.begin(), p.x.end());
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

}  // namespace runout::render

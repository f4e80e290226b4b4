// Off-screen OpenGL drawing of discs and wall segments through OSMesa (llvmpipe, no display, no
// GPU). Knows only primitives: the caller maps physics to colours (frame.hpp).
#pragma once

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "runout/render/image.hpp"

namespace runout::render {

class RenderError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// World window shown by a frame: lower-left corner (m) and scale (pixels per metre).
struct View {
  double x0 = 0, y0 = 0;
  double scale = 1;
  bool operator==(const View&) const = default;
};

// Discs to draw, in world metres; colour as RGBA8.
struct DiscBatch {
  std::vector<float> x, y, radius, angle;
  std::vector<Rgba> colour;
  void clear() { x.clear(); y.clear(); radius.clear(); angle.clear(); colour.clear(); }
  void add(double px, double py, double r, double a, Rgba c) {
    x.push_back(static_cast<float>(px)); y.push_back(static_cast<float>(py));
    radius.push_back(static_cast<float>(r)); angle.push_back(static_cast<float>(a));
    colour.push_back(c);
  }
  std::size_t size() const { return x.size(); }
};

struct SegmentLine {
  double ax, ay, bx, by;
  bool operator==(const SegmentLine&) const = default;
};

enum class DiscMethod { point_sprites, quads };

struct DrawStyle {
  Rgba background = {255, 255, 255, 255};  // alpha 0: transparent
  double outline_px = 0;                   // 0: no outline
  bool spokes = false;
  Rgba ink = {30, 30, 30, 255};            // spokes
  Rgba wall = {51, 51, 51, 255};
  double wall_half_width_px = 1.5;
  bool operator==(const DrawStyle&) const = default;
};

class GlRenderer {
 public:
  // Makes an OSMesa core-profile (3.3) context of the given size. Throws RenderError with the
  // reason if OSMesa is missing or refuses.
  GlRenderer(int width, int height);
  ~GlRenderer();
  GlRenderer(const GlRenderer&) = delete;
  GlRenderer& operator=(const GlRenderer&) = delete;

  int width() const { return width_; }
  int height() const { return height_; }
  void set_method(DiscMethod m) { method_ = m; }
  DiscMethod method() const { return method_; }

  // Draws one frame and returns it (top row first): the renderer's own buffer, valid until the
  // next draw, which the caller may draw over (the overlays) or copy. Discs larger than the
  // point-size limit (255 px) are drawn as quads whatever the method. When the view, walls,
  // style and method are those of the last frame, only the rectangle the discs covered then or
  // cover now is cleared and redrawn: the same pixels, at a fraction of a whole clear.
  Image& draw(const View& view, const DiscBatch& discs, const std::vector<SegmentLine>& walls,
             const DrawStyle& style);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int width_, height_;
  DiscMethod method_ = DiscMethod::point_sprites;
};

}  // namespace runout::render

// The few primitives overlays and vector pictures are drawn with, in frame pixels (origin at
// the top left, y down). A PNG's overlays are blended onto the OpenGL frame through one
// (frame.cpp); a PDF (cairo) or SVG draws the whole frame through another (vector.cpp), so the
// legend, colour bar, t* stamp and scale bar are laid out once for every format.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>

#include "runout/render/image.hpp"

namespace runout::render {

enum class PictureFormat { png, pdf, svg };
PictureFormat parse_picture_format(const std::string& s);  // throws std::invalid_argument
const char* extension(PictureFormat f);                   // "png", "pdf", "svg"

class Canvas {
 public:
  virtual ~Canvas() = default;
  virtual void rect(int x0, int y0, int x1, int y1, Rgba colour) = 0;  // [x0, x1) x [y0, y1)
  virtual void disc(double cx, double cy, double r, Rgba colour) = 0;
  // UTF-8 text in DejaVu Sans, `pixel_size` the em size, the left end of its baseline at (x, y).
  virtual void text(int x, int y, std::string_view utf8, int pixel_size, Rgba colour) = 0;
};

}  // namespace runout::render

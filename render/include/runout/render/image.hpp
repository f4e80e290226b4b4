// An RGBA8 image, top row first, and what we do with it outside OpenGL: PNG files (libpng) and
// tolerant comparison for visual regression tests (matplotlib's habit: a threshold per pixel,
// a share of differing pixels allowed, a diff image on failure).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace runout::render {

struct Rgba {
  std::uint8_t r = 0, g = 0, b = 0, a = 255;
  bool operator==(const Rgba&) const = default;
};

struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;  // width * height * 4, rows top to bottom

  Image() = default;
  Image(int w, int h, Rgba fill = {255, 255, 255, 255});
  // Sized, every byte 0: for an image about to be overwritten whole (the OpenGL read-back),
  // where filling it white first cost a pass over 3.7 MB a 1280x720 frame.
  static Image zeroed(int w, int h) {
    Image img;
    img.width = w;
    img.height = h;
    img.rgba.resize(static_cast<std::size_t>(w) * h * 4);
    return img;
  }
  Rgba at(int x, int y) const {
    const std::uint8_t* p = &rgba[(static_cast<std::size_t>(y) * width + x) * 4];
    return {p[0], p[1], p[2], p[3]};
  }
  void set(int x, int y, Rgba c) {
    std::uint8_t* p = &rgba[(static_cast<std::size_t>(y) * width + x) * 4];
    p[0] = c.r; p[1] = c.g; p[2] = c.b; p[3] = c.a;
  }
  // Source-over blend of colour c with coverage `alpha` in [0, 1].
  void blend(int x, int y, Rgba c, double alpha);
  // The same for a coverage in 0-255 (text, rectangles), in integers: the bytes blend() gives
  // with alpha = coverage / 255, at a fraction of its cost.
  void blend_coverage(int x, int y, Rgba c, int coverage);
  void fill_rect(int x0, int y0, int x1, int y1, Rgba c);  // [x0, x1) x [y0, y1), clipped
};

// PNG encoding tuned for speed (the Up filter, ISA-L's igzip at level 1): a whole-domain frame
// in well under a millisecond, for files a quarter larger than zlib's fastest level gives.
// With `keep_alpha` false the alpha channel is dropped.
std::string encode_png(const Image& image, bool keep_alpha);
// Written atomically (temp file + rename). Throws IoError naming the path.
void write_png(const std::string& path, const Image& image, bool keep_alpha = false);
// Reads any 8-bit PNG into RGBA. Throws IoError naming the path.
Image read_png(const std::string& path);

struct CompareOptions {
  int pixel_threshold = 24;     // a pixel differs if any channel differs by more (0-255)
  double max_share = 0.002;     // the images match if at most this share of pixels differ
};
struct Comparison {
  bool same_size = false;
  long differing_pixels = 0;
  double share = 0;          // differing / all
  double rms = 0;            // over all channels, 0-255 units
  int max_difference = 0;
  bool match = false;
  Image diff;                // differing pixels red over a faded copy of the expected image
};
Comparison compare_images(const Image& expected, const Image& actual, const CompareOptions& o = {});

}  // namespace runout::render

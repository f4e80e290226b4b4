#include "runout/render/image.hpp"

#include <png.h>
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <csetjmp>
#include <cstring>

#include "runout/errors.hpp"
#include "runout/io/files.hpp"

namespace runout::render {

Image::Image(int w, int h, Rgba fill) : width(w), height(h), rgba(static_cast<std::size_t>(w) * h * 4) {
  for (std::size_t k = 0; k < rgba.size(); k += 4) {
    rgba[k] = fill.r; rgba[k + 1] = fill.g; rgba[k + 2] = fill.b; rgba[k + 3] = fill.a;
  }
}

void Image::blend(int x, int y, Rgba c, double alpha) {
  if (x < 0 || y < 0 || x >= width || y >= height || alpha <= 0) return;
  alpha = std::min(alpha, 1.0) * (c.a / 255.0);
  std::uint8_t* p = &rgba[(static_cast<std::size_t>(y) * width + x) * 4];
  auto mix = [alpha](std::uint8_t dst, std::uint8_t src) {
    return static_cast<std::uint8_t>(std::lround(dst + (src - dst) * alpha));
  };
  p[0] = mix(p[0], c.r); p[1] = mix(p[1], c.g); p[2] = mix(p[2], c.b);
  p[3] = static_cast<std::uint8_t>(std::lround(p[3] + (255 - p[3]) * alpha));
}

namespace {

// dst + (src - dst) w / 65025, rounded to the nearest integer, for a weight w = coverage x alpha
// (each 0-255). The same bytes as blend() with alpha = coverage / 255: a fraction over 65025
// (odd) is never exactly half way, so rounding in integers and lround in double agree
// (checked for every dst, src, coverage and alpha); without a libm call or a double per channel.
void mix_pixel(std::uint8_t* p, Rgba c, int w) {
  auto mix = [w](int dst, int src) { return static_cast<std::uint8_t>((dst * 65025 + (src - dst) * w + 32512) / 65025); };
  p[0] = mix(p[0], c.r); p[1] = mix(p[1], c.g); p[2] = mix(p[2], c.b); p[3] = mix(p[3], 255);
}

}  // namespace

void Image::blend_coverage(int x, int y, Rgba c, int coverage) {
  if (x < 0 || y < 0 || x >= width || y >= height || coverage <= 0) return;
  mix_pixel(&rgba[(static_cast<std::size_t>(y) * width + x) * 4], c, std::min(coverage, 255) * c.a);
}

void Image::fill_rect(int x0, int y0, int x1, int y1, Rgba c) {
  x0 = std::max(x0, 0); y0 = std::max(y0, 0);
  x1 = std::min(x1, width); y1 = std::min(y1, height);
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) mix_pixel(&rgba[(static_cast<std::size_t>(y) * width + x) * 4], c, 255 * c.a);
}

namespace {

struct PngWriteState {
  std::string out;
};

void png_append(png_structp png, png_bytep data, png_size_t n) {
  auto* s = static_cast<PngWriteState*>(png_get_io_ptr(png));
  s->out.append(reinterpret_cast<const char*>(data), n);
}
void png_no_flush(png_structp) {}

[[noreturn]] void png_fail(png_structp png, png_const_charp msg) {
  auto* where = static_cast<std::string*>(png_get_error_ptr(png));
  if (where) *where = msg;
  png_longjmp(png, 1);
}

}  // namespace

std::string encode_png(const Image& image, bool keep_alpha) {
  std::string error;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &error, png_fail, nullptr);
  if (!png) throw IoError("PNG: out of memory");
  png_infop info = png_create_info_struct(png);
  PngWriteState state;
  state.out.reserve(static_cast<std::size_t>(image.width) * image.height / 8);  // a frame is ~5-40 % of its RGB
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    throw IoError("PNG encoding failed: " + error);
  }
  png_set_write_fn(png, &state, png_append, png_no_flush);
  png_set_IHDR(png, info, image.width, image.height, 8,
               keep_alpha ? PNG_COLOR_TYPE_RGBA : PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  // Measured here (shared notes): level 1 + Up + RLE is ~4x faster than the defaults.
  png_set_compression_level(png, 1);
  png_set_compression_strategy(png, Z_RLE);
  png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_UP);
  // zlib's output in 1 MB pieces rather than libpng's 8 kB: one call to png_append per frame.
  png_set_compression_buffer_size(png, 1 << 20);
  png_write_info(png, info);
  // RGB: libpng drops the fourth byte of each pixel itself (png_set_filler), so the rows go in
  // as they are, with no copy into an RGB row first.
  if (!keep_alpha) png_set_filler(png, 0, PNG_FILLER_AFTER);
  for (int y = 0; y < image.height; ++y)
    png_write_row(png, const_cast<png_bytep>(&image.rgba[static_cast<std::size_t>(y) * image.width * 4]));
  png_write_end(png, info);
  png_destroy_write_struct(&png, &info);
  return std::move(state.out);
}

void write_png(const std::string& path, const Image& image, bool keep_alpha) {
  io::write_file_atomically(path, encode_png(image, keep_alpha));
}

Image read_png(const std::string& path) {
  const std::string bytes = io::read_file(path);
  png_image img;
  std::memset(&img, 0, sizeof img);
  img.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_memory(&img, bytes.data(), bytes.size()))
    throw IoError(path + ": not a readable PNG (" + img.message + ")");
  img.format = PNG_FORMAT_RGBA;
  Image out;
  out.width = static_cast<int>(img.width);
  out.height = static_cast<int>(img.height);
  out.rgba.resize(PNG_IMAGE_SIZE(img));
  if (!png_image_finish_read(&img, nullptr, out.rgba.data(), 0, nullptr)) {
    const std::string why = img.message;
    png_image_free(&img);
    throw IoError(path + ": corrupt PNG (" + why + ")");
  }
  return out;
}

Comparison compare_images(const Image& expected, const Image& actual, const CompareOptions& o) {
  Comparison c;
  c.same_size = expected.width == actual.width && expected.height == actual.height;
  if (!c.same_size) return c;
  c.diff = Image(expected.width, expected.height);
  double sum2 = 0;
  for (int y = 0; y < expected.height; ++y)
    for (int x = 0; x < expected.width; ++x) {
      const Rgba e = expected.at(x, y), a = actual.at(x, y);
      const int d[4] = {std::abs(e.r - a.r), std::abs(e.g - a.g), std::abs(e.b - a.b), std::abs(e.a - a.a)};
      const int worst = *std::max_element(d, d + 4);
      for (int v : d) sum2 += double(v) * v;
      c.max_difference = std::max(c.max_difference, worst);
      const bool differs = worst > o.pixel_threshold;
      c.differing_pixels += differs;
      // Faded expected image, differing pixels in red.
      const auto fade = [](std::uint8_t v) { return static_cast<std::uint8_t>(191 + v / 4); };
      c.diff.set(x, y, differs ? Rgba{220, 0, 0, 255} : Rgba{fade(e.r), fade(e.g), fade(e.b), 255});
    }
  const double pixels = double(expected.width) * expected.height;
  c.share = pixels > 0 ? c.differing_pixels / pixels : 0.0;
  c.rms = pixels > 0 ? std::sqrt(sum2 / (pixels * 4)) : 0.0;
  c.match = c.share <= o.max_share;
  return c;
}

}  // namespace runout::render

#include "runout/render/image.hpp"

#include <isa-l/igzip_lib.h>
#include <png.h>

#include <algorithm>
#include <cmath>
#include <csetjmp>
#include <cstring>
#include <memory>
#include <vector>

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

// One PNG row from RGBA pixels: the filter byte, then for each pixel its first C channels minus
// those of the pixel above (the Up filter, PNG spec filter type 2: flat colour and background
// become runs of zeros), or as they are on the first row (filter type 0).
template <int C>
void filter_row(unsigned char* out, const std::uint8_t* row, const std::uint8_t* above, int width) {
  *out++ = above ? 2 : 0;
  if (above) {
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < C; ++c) out[x * C + c] = static_cast<unsigned char>(row[4 * x + c] - above[4 * x + c]);
  } else {
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < C; ++c) out[x * C + c] = row[4 * x + c];
  }
}

// The zlib stream (RFC 1950) of a frame's filtered rows, by ISA-L's igzip at level 1: on a
// whole-domain frame (mostly background) 16x faster than zlib's level 1 + Z_RLE, for files
// about a quarter larger (docs/performance_log.md, issue 12, ninth session). igzip writes the
// zlib header and the Adler-32 itself.
std::string deflate_rows(const Image& image, int channels) {
  const std::size_t row_bytes = 1 + static_cast<std::size_t>(image.width) * channels;
  const std::size_t raw = row_bytes * image.height;
  std::vector<std::uint8_t> level_buffer(ISAL_DEF_LVL1_DEFAULT);
  isal_zstream z;
  isal_deflate_init(&z);
  z.level = 1;
  z.level_buf = level_buffer.data();
  z.level_buf_size = static_cast<std::uint32_t>(level_buffer.size());
  z.gzip_flag = IGZIP_ZLIB;
  // Room for stored blocks (5 bytes per 64 KiB) and the wrapper: never too small. Not zeroed,
  // so the pages the ~50 KB of output never reach are never touched.
  const std::size_t capacity = raw + raw / 8192 + 64;
  std::unique_ptr<std::uint8_t[]> out(new std::uint8_t[capacity]);
  z.next_out = out.get();
  z.avail_out = static_cast<std::uint32_t>(capacity);
  // A few rows at a time, so the filtered bytes are still in cache when igzip reads them.
  constexpr int kRowsPerChunk = 8;
  std::vector<unsigned char> chunk(row_bytes * kRowsPerChunk);
  const std::size_t stride = static_cast<std::size_t>(image.width) * 4;
  for (int y = 0; y < image.height; y += kRowsPerChunk) {
    const int rows = std::min(kRowsPerChunk, image.height - y);
    for (int k = 0; k < rows; ++k) {
      const std::uint8_t* row = &image.rgba[(y + k) * stride];
      if (channels == 4) filter_row<4>(&chunk[k * row_bytes], row, y + k > 0 ? row - stride : nullptr, image.width);
      else filter_row<3>(&chunk[k * row_bytes], row, y + k > 0 ? row - stride : nullptr, image.width);
    }
    z.next_in = chunk.data();
    z.avail_in = static_cast<std::uint32_t>(row_bytes * rows);
    z.end_of_stream = y + rows >= image.height;
    if (isal_deflate(&z) != COMP_OK || z.avail_in != 0)
      throw IoError("PNG encoding failed: igzip could not deflate the image data");
  }
  if (z.internal_state.state != ZSTATE_END) throw IoError("PNG encoding failed: igzip did not finish the stream");
  return std::string(reinterpret_cast<const char*>(out.get()), capacity - z.avail_out);
}

}  // namespace

std::string encode_png(const Image& image, bool keep_alpha) {
  const std::string zdata = deflate_rows(image, keep_alpha ? 4 : 3);

  // The file around it is libpng's: signature and header, the data as one IDAT chunk, the end.
  std::string error;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &error, png_fail, nullptr);
  if (!png) throw IoError("PNG: out of memory");
  png_infop info = png_create_info_struct(png);
  PngWriteState state;
  state.out.reserve(zdata.size() + 128);
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    throw IoError("PNG encoding failed: " + error);
  }
  png_set_write_fn(png, &state, png_append, png_no_flush);
  png_set_IHDR(png, info, image.width, image.height, 8, keep_alpha ? PNG_COLOR_TYPE_RGBA : PNG_COLOR_TYPE_RGB,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  png_write_chunk(png, reinterpret_cast<png_const_bytep>("IDAT"), reinterpret_cast<png_const_bytep>(zdata.data()),
                  zdata.size());
  png_write_chunk(png, reinterpret_cast<png_const_bytep>("IEND"), nullptr, 0);
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

#include "runout/render/image.hpp"

#include <libdeflate.h>
#include <png.h>
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <csetjmp>
#include <cstring>
#include <memory>
#include <thread>

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

// A frame's image data is deflated in up to this many strips side by side (fixed by the height,
// so a frame's bytes do not depend on the machine).
constexpr int kPngStrips = 4;

// One horizontal strip of a PNG's image data: its rows filtered (Up) and deflated as a raw
// DEFLATE piece that ends on a byte boundary (the pigz construction, with zlib's own calls),
// and the Adler-32 of its filtered bytes, which zlib can combine across strips.
struct PngStrip {
  std::unique_ptr<unsigned char[]> deflated;  // not zero-filled: deflateBound is ~the raw size
  std::size_t size = 0;
  uLong adler = 1;
  std::string error;
};

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

void deflate_strip(const Image& image, int channels, int y0, int y1, bool last, PngStrip& strip) {
  const std::size_t row_bytes = 1 + static_cast<std::size_t>(image.width) * channels;
  z_stream z{};
  // Level 1 + run-length matches: ~4x faster than libpng's defaults here (shared notes).
  if (deflateInit2(&z, 1, Z_DEFLATED, -15, 8, Z_RLE) != Z_OK) {
    strip.error = "zlib: out of memory";
    return;
  }
  const std::size_t capacity = deflateBound(&z, row_bytes * (y1 - y0)) + 16;
  strip.deflated.reset(new unsigned char[capacity]);
  z.next_out = strip.deflated.get();
  z.avail_out = static_cast<uInt>(capacity);
  // A few rows at a time, so the filtered bytes are still in cache when zlib reads them.
  constexpr int kRowsPerChunk = 8;
  std::vector<unsigned char> chunk(row_bytes * kRowsPerChunk);
  const std::size_t stride = static_cast<std::size_t>(image.width) * 4;
  for (int y = y0; y < y1; y += kRowsPerChunk) {
    const int rows = std::min(kRowsPerChunk, y1 - y);
    for (int k = 0; k < rows; ++k) {
      const std::uint8_t* row = &image.rgba[(y + k) * stride];
      if (channels == 4) filter_row<4>(&chunk[k * row_bytes], row, y + k > 0 ? row - stride : nullptr, image.width);
      else filter_row<3>(&chunk[k * row_bytes], row, y + k > 0 ? row - stride : nullptr, image.width);
    }
    const std::size_t n = row_bytes * rows;
    // libdeflate's Adler-32 is vectorised: 0.15 ms a frame against zlib's 1.4 (docs/performance.md).
    strip.adler = libdeflate_adler32(static_cast<std::uint32_t>(strip.adler), chunk.data(), n);
    z.next_in = chunk.data();
    z.avail_in = static_cast<uInt>(n);
    const bool end = y + rows >= y1;
    // A strip that is not the last ends with a sync flush: every block so far is non-final and
    // the piece ends on a byte boundary, so the next strip's blocks can follow it directly.
    const int r = deflate(&z, end ? (last ? Z_FINISH : Z_SYNC_FLUSH) : Z_NO_FLUSH);
    if (r == Z_STREAM_ERROR || z.avail_in != 0 || (end && last && r != Z_STREAM_END)) {
      strip.error = "zlib: deflate failed";
      break;
    }
  }
  strip.size = capacity - z.avail_out;
  deflateEnd(&z);
}

}  // namespace

std::string encode_png(const Image& image, bool keep_alpha) {
  const int channels = keep_alpha ? 4 : 3;
  // The image data in a fixed number of strips for the frame's height, whatever the machine,
  // so a frame's file has the same bytes everywhere; the strips are deflated side by side.
  const int strips = std::clamp(image.height / 64, 1, kPngStrips);
  std::vector<PngStrip> parts(strips);
  auto strip_rows = [&](int k) { return static_cast<int>(static_cast<long>(image.height) * k / strips); };
  {
    const int workers = std::clamp(static_cast<int>(std::thread::hardware_concurrency()), 1, strips);
    std::vector<std::thread> helpers;
    auto work = [&](int w) {
      for (int k = w; k < strips; k += workers)
        deflate_strip(image, channels, strip_rows(k), strip_rows(k + 1), k == strips - 1, parts[k]);
    };
    for (int w = 1; w < workers; ++w) helpers.emplace_back(work, w);
    work(0);
    for (auto& t : helpers) t.join();
  }
  // The zlib stream (RFC 1950): a two-byte header (deflate, 32 KiB window, fastest level), the
  // strips' DEFLATE pieces, and the Adler-32 of all filtered bytes, combined by zlib.
  std::string zdata = {'\x78', '\x01'};
  uLong adler = 1;
  for (int k = 0; k < strips; ++k) {
    if (!parts[k].error.empty()) throw IoError("PNG encoding failed: " + parts[k].error);
    zdata.append(reinterpret_cast<const char*>(parts[k].deflated.get()), parts[k].size);
    const std::size_t bytes = static_cast<std::size_t>(strip_rows(k + 1) - strip_rows(k)) * (1 + image.width * channels);
    adler = k == 0 ? parts[k].adler : adler32_combine(adler, parts[k].adler, static_cast<z_off_t>(bytes));
  }
  for (int shift = 24; shift >= 0; shift -= 8) zdata.push_back(static_cast<char>((adler >> shift) & 0xff));

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

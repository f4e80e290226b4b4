#include "runout/render/vector.hpp"

#include <cairo-pdf.h>
#include <cairo.h>

#include <cmath>
#include <cstdio>

#include "runout/render/gl_renderer.hpp"

namespace runout::render {

PictureFormat parse_picture_format(const std::string& s) {
  if (s == "png") return PictureFormat::png;
  if (s == "pdf") return PictureFormat::pdf;
  if (s == "svg") return PictureFormat::svg;
  throw std::invalid_argument("picture format \"" + s + "\" is not one of png, pdf, svg");
}

const char* extension(PictureFormat f) {
  switch (f) {
    case PictureFormat::png: return "png";
    case PictureFormat::pdf: return "pdf";
    case PictureFormat::svg: return "svg";
  }
  return "?";
}

namespace {

constexpr double kTwoPi = 6.283185307179586;

// The canvas of a whole vector frame: the overlay primitives plus the scene's strokes.
class VectorCanvas : public Canvas {
 public:
  // A straight stroke; square caps reach half the width past each end (the walls' quads).
  virtual void line(double ax, double ay, double bx, double by, double width, bool square_caps, Rgba c) = 0;
  virtual void ring(double cx, double cy, double r, double width, Rgba c) = 0;  // a stroked circle
};

// The scene as GlRenderer draws it (gl_renderer.cpp, shaders/disc.frag): the world window
// mapped to pixels with y up, walls under the discs, a disc's rim darkened to 0.55 of its
// colour over outline_px, and the spoke a line from the centre to the edge along its angle.
void paint_scene(VectorCanvas& c, int width, int height, const FramePlan& plan, const DrawStyle& style) {
  const View& v = plan.view;
  auto px = [&](double x) { return (x - v.x0) * v.scale; };
  auto py = [&](double y) { return height - (y - v.y0) * v.scale; };
  if (style.background.a > 0) c.rect(0, 0, width, height, style.background);
  for (const auto& s : plan.walls)
    c.line(px(s.ax), py(s.ay), px(s.bx), py(s.by), 2 * style.wall_half_width_px, true, style.wall);
  const DiscBatch& d = plan.discs;
  for (std::size_t k = 0; k < d.size(); ++k) {
    const double cx = px(d.x[k]), cy = py(d.y[k]), r = d.radius[k] * v.scale;
    const Rgba colour = d.colour[k];
    c.disc(cx, cy, r, colour);
    if (style.outline_px > 0) {
      const Rgba rim{static_cast<std::uint8_t>(colour.r * 0.55), static_cast<std::uint8_t>(colour.g * 0.55),
                     static_cast<std::uint8_t>(colour.b * 0.55), colour.a};
      const double w = std::min(style.outline_px, r);
      c.ring(cx, cy, r - 0.5 * w, w, rim);
    }
    if (style.spokes && r >= 3.0) {
      const double half = std::max(0.6, 0.09 * r);
      c.line(cx, cy, cx + r * std::cos(d.angle[k]), cy - r * std::sin(d.angle[k]), 2 * half, false, style.ink);
    }
  }
}

// ---- PDF through cairo ----

cairo_status_t append_bytes(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

class CairoCanvas : public VectorCanvas {
 public:
  explicit CairoCanvas(cairo_t* cr) : cr_(cr) {
    // Cairo's toy API finds the font through fontconfig; cairo embeds a subset of it and keeps
    // the text as text (pdftotext reads it back).
    cairo_select_font_face(cr_, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  }
  void rect(int x0, int y0, int x1, int y1, Rgba c) override {
    source(c);
    cairo_rectangle(cr_, x0, y0, x1 - x0, y1 - y0);
    cairo_fill(cr_);
  }
  void disc(double cx, double cy, double r, Rgba c) override {
    source(c);
    cairo_new_path(cr_);
    cairo_arc(cr_, cx, cy, r, 0, kTwoPi);
    cairo_fill(cr_);
  }
  void text(int x, int y, std::string_view utf8, int pixel_size, Rgba c) override {
    source(c);
    cairo_set_font_size(cr_, pixel_size);
    cairo_move_to(cr_, x, y);
    const std::string s(utf8);
    cairo_show_text(cr_, s.c_str());
    cairo_new_path(cr_);
  }
  void line(double ax, double ay, double bx, double by, double width, bool square_caps, Rgba c) override {
    source(c);
    cairo_set_line_width(cr_, width);
    cairo_set_line_cap(cr_, square_caps ? CAIRO_LINE_CAP_SQUARE : CAIRO_LINE_CAP_BUTT);
    cairo_move_to(cr_, ax, ay);
    cairo_line_to(cr_, bx, by);
    cairo_stroke(cr_);
  }
  void ring(double cx, double cy, double r, double width, Rgba c) override {
    source(c);
    cairo_set_line_width(cr_, width);
    cairo_new_path(cr_);
    cairo_arc(cr_, cx, cy, r, 0, kTwoPi);
    cairo_stroke(cr_);
  }

 private:
  void source(Rgba c) {
    if (c.a == 255) cairo_set_source_rgb(cr_, c.r / 255.0, c.g / 255.0, c.b / 255.0);
    else cairo_set_source_rgba(cr_, c.r / 255.0, c.g / 255.0, c.b / 255.0, c.a / 255.0);
  }
  cairo_t* cr_;
};

std::string encode_pdf(int width, int height, const FramePlan& plan, const DrawStyle& style,
                       const std::function<void(Canvas&)>& overlays) {
  std::string out;
  cairo_surface_t* surface = cairo_pdf_surface_create_for_stream(append_bytes, &out, width, height);
  // The same frame gives the same bytes: no creation date in the file.
  cairo_pdf_surface_set_metadata(surface, CAIRO_PDF_METADATA_CREATOR, "runout");
  cairo_pdf_surface_set_metadata(surface, CAIRO_PDF_METADATA_CREATE_DATE, "");
  cairo_t* cr = cairo_create(surface);
  {
    CairoCanvas canvas(cr);
    paint_scene(canvas, width, height, plan, style);
    overlays(canvas);
  }
  const cairo_status_t drawn = cairo_status(cr);
  cairo_destroy(cr);
  cairo_surface_finish(surface);
  const cairo_status_t finished = cairo_surface_status(surface);
  cairo_surface_destroy(surface);
  if (drawn != CAIRO_STATUS_SUCCESS || finished != CAIRO_STATUS_SUCCESS)
    throw RenderError(std::string("cairo: cannot draw the PDF: ") +
                      cairo_status_to_string(drawn != CAIRO_STATUS_SUCCESS ? drawn : finished));
  return out;
}

// ---- SVG as XML ----

// Written directly rather than through cairo's SVG surface, which turns text into glyph
// outlines (<symbol>/<use>) and circles into Bézier paths: here a disc is a <circle> and a
// label a <text>, which editors (Inkscape, a browser) keep as such.
class SvgCanvas : public VectorCanvas {
 public:
  explicit SvgCanvas(std::string& out) : out_(out) {}
  void rect(int x0, int y0, int x1, int y1, Rgba c) override {
    put("<rect x=\"%d\" y=\"%d\" width=\"%d\" height=\"%d\"", x0, y0, x1 - x0, y1 - y0);
    out_ += fill(c) + "/>\n";
  }
  void disc(double cx, double cy, double r, Rgba c) override {
    put("<circle cx=\"%.2f\" cy=\"%.2f\" r=\"%.2f\"", cx, cy, r);
    out_ += fill(c) + "/>\n";
  }
  void text(int x, int y, std::string_view utf8, int pixel_size, Rgba c) override {
    put("<text x=\"%d\" y=\"%d\" font-family=\"DejaVu Sans\" font-size=\"%d\"", x, y, pixel_size);
    out_ += fill(c) + " xml:space=\"preserve\">";
    for (char ch : utf8) {
      if (ch == '&') out_ += "&amp;";
      else if (ch == '<') out_ += "&lt;";
      else if (ch == '>') out_ += "&gt;";
      else out_ += ch;
    }
    out_ += "</text>\n";
  }
  void line(double ax, double ay, double bx, double by, double width, bool square_caps, Rgba c) override {
    put("<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" stroke-width=\"%.2f\" stroke-linecap=\"%s\"", ax, ay,
        bx, by, width, square_caps ? "square" : "butt");
    out_ += stroke(c) + "/>\n";
  }
  void ring(double cx, double cy, double r, double width, Rgba c) override {
    put("<circle cx=\"%.2f\" cy=\"%.2f\" r=\"%.2f\" fill=\"none\" stroke-width=\"%.2f\"", cx, cy, r, width);
    out_ += stroke(c) + "/>\n";
  }

 private:
  template <class... A>
  void put(const char* format, A... args) {
    char buf[256];
    std::snprintf(buf, sizeof buf, format, args...);
    out_ += buf;
  }
  static std::string colour(const char* attribute, Rgba c) {
    char buf[64];
    std::snprintf(buf, sizeof buf, " %s=\"#%02x%02x%02x\"", attribute, c.r, c.g, c.b);
    std::string s = buf;
    if (c.a != 255) {
      std::snprintf(buf, sizeof buf, " %s-opacity=\"%.3f\"", attribute, c.a / 255.0);
      s += buf;
    }
    return s;
  }
  static std::string fill(Rgba c) { return colour("fill", c); }
  static std::string stroke(Rgba c) { return colour("stroke", c); }
  std::string& out_;
};

std::string encode_svg(int width, int height, const FramePlan& plan, const DrawStyle& style,
                       const std::function<void(Canvas&)>& overlays) {
  std::string out;
  out.reserve(plan.discs.size() * 64 + 4096);
  char head[256];
  std::snprintf(head, sizeof head,
                "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
                "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" height=\"%d\" viewBox=\"0 0 %d %d\">\n",
                width, height, width, height);
  out += head;
  SvgCanvas canvas(out);
  paint_scene(canvas, width, height, plan, style);
  overlays(canvas);
  out += "</svg>\n";
  return out;
}

}  // namespace

std::string encode_vector(PictureFormat format, int width, int height, const FramePlan& plan,
                          const DrawStyle& style, const std::function<void(Canvas&)>& overlays) {
  switch (format) {
    case PictureFormat::pdf: return encode_pdf(width, height, plan, style, overlays);
    case PictureFormat::svg: return encode_svg(width, height, plan, style, overlays);
    case PictureFormat::png: break;
  }
  throw std::invalid_argument("encode_vector: a PNG is drawn by FrameMaker::draw");
}

}  // namespace runout::render

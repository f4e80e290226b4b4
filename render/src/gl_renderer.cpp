#define GL_GLEXT_PROTOTYPES 1
#include "runout/render/gl_renderer.hpp"

#include <GL/osmesa.h>
#include <GL/gl.h>
#include <GL/glext.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "shaders.inc"  // kDiscVert, kDiscFrag, kSegmentVert, kSegmentFrag (from shaders/)

namespace runout::render {

namespace {

// Discs whose centre is outside the viewport would be culled whole as point sprites, so the
// viewport extends this far beyond the frame on every side (shared notes); OpenGL draws only
// what falls on the frame itself.
constexpr int kGuard = 16;
constexpr float kMaxPointSize = 255.0f;

GLuint compile(GLenum type, const char* source, const char* name) {
  const GLuint s = glCreateShader(type);
  glShaderSource(s, 1, &source, nullptr);
  glCompileShader(s);
  GLint ok = 0;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048];
    glGetShaderInfoLog(s, sizeof log, nullptr, log);
    throw RenderError(std::string("OpenGL: shader ") + name + " does not compile: " + log);
  }
  return s;
}

GLuint link(const char* vert, const char* frag, const char* name) {
  const GLuint p = glCreateProgram();
  const GLuint v = compile(GL_VERTEX_SHADER, vert, name), f = compile(GL_FRAGMENT_SHADER, frag, name);
  glAttachShader(p, v);
  glAttachShader(p, f);
  glLinkProgram(p);
  glDeleteShader(v);
  glDeleteShader(f);
  GLint ok = 0;
  glGetProgramiv(p, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[2048];
    glGetProgramInfoLog(p, sizeof log, nullptr, log);
    throw RenderError(std::string("OpenGL: program ") + name + " does not link: " + log);
  }
  return p;
}

// A rectangle of window pixels (OpenGL's: x right, y up from the frame's bottom row), [x0, x1)
// x [y0, y1).
struct PixelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool empty() const { return x1 <= x0 || y1 <= y0; }
  PixelRect joined(const PixelRect& o) const {
    if (empty()) return o;
    if (o.empty()) return *this;
    return {std::min(x0, o.x0), std::min(y0, o.y0), std::max(x1, o.x1), std::max(y1, o.y1)};
  }
};

// The pixels the discs can touch in a frame of w x h: each disc's square of half-side r + 1 px
// (the shader's anti-aliased margin), one more pixel for rounding, clipped to the frame.
PixelRect disc_pixels(const View& view, const DiscBatch& discs, int w, int h) {
  if (discs.size() == 0) return {};
  double lo_x = INFINITY, lo_y = INFINITY, hi_x = -INFINITY, hi_y = -INFINITY;
  for (std::size_t k = 0; k < discs.size(); ++k) {
    const double cx = (discs.x[k] - view.x0) * view.scale, cy = (discs.y[k] - view.y0) * view.scale;
    if (!std::isfinite(cx) || !std::isfinite(cy)) continue;
    const double half = discs.radius[k] * view.scale + 2.0;
    lo_x = std::min(lo_x, cx - half); hi_x = std::max(hi_x, cx + half);
    lo_y = std::min(lo_y, cy - half); hi_y = std::max(hi_y, cy + half);
  }
  auto clip = [](double v, int n) { return static_cast<int>(std::clamp(v, 0.0, static_cast<double>(n))); };
  return {clip(std::floor(lo_x), w), clip(std::floor(lo_y), h), clip(std::ceil(hi_x), w), clip(std::ceil(hi_y), h)};
}

// OpenGL blends in premultiplied alpha; a PNG stores straight alpha.
void unpremultiply(Image& image) {
  std::uint8_t* p = image.rgba.data();
  for (std::size_t k = 0; k < image.rgba.size(); k += 4) {
    const int alpha = p[k + 3];
    if (alpha > 0 && alpha < 255)
      for (int c = 0; c < 3; ++c) p[k + c] = static_cast<std::uint8_t>(std::min(255, (p[k + c] * 255 + alpha / 2) / alpha));
  }
}

}  // namespace

struct GlRenderer::Impl {
  OSMesaContext context = nullptr;
  // OSMesa's colour buffer is the frame itself: OpenGL's pixels land where the overlays and the
  // encoders read them, with no copy out of a larger surface and no new frame per draw.
  Image frame;
  GLuint disc_program = 0, segment_program = 0;
  GLuint vao = 0, disc_buffers[5] = {}, quad_corner_buffer = 0, segment_buffer = 0;
  std::vector<float> scratch;
  // What the colour buffer holds from the last frame: drawn with these, its discs within
  // last_discs. Everything outside them is background and walls, which a frame like it keeps.
  bool drawn = false;
  View last_view;
  DrawStyle last_style;
  std::vector<SegmentLine> last_walls;
  DiscMethod last_method = DiscMethod::point_sprites;
  PixelRect last_discs;

  void make_current() {
    if (!OSMesaMakeCurrent(context, frame.rgba.data(), GL_UNSIGNED_BYTE, frame.width, frame.height))
      throw RenderError("OpenGL: OSMesaMakeCurrent failed");
    OSMesaPixelStore(OSMESA_Y_UP, 0);  // rows top to bottom, as Image has them, at no cost
  }
};

GlRenderer::GlRenderer(int width, int height) : impl_(std::make_unique<Impl>()), width_(width), height_(height) {
  if (width <= 0 || height <= 0 || width > 8192 || height > 8192)
    throw RenderError("frame size " + std::to_string(width) + "x" + std::to_string(height) +
                      " is outside 1..8192");
  const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 0, OSMESA_STENCIL_BITS, 0,
                         OSMESA_ACCUM_BITS, 0, OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                         OSMESA_CONTEXT_MAJOR_VERSION, 3, OSMESA_CONTEXT_MINOR_VERSION, 3, 0};
  auto& m = *impl_;
  m.context = OSMesaCreateContextAttribs(attribs, nullptr);
  if (!m.context)
    throw RenderError("OpenGL: cannot create an OSMesa core-profile 3.3 context "
                      "(is libosmesa6 installed and Mesa 17 or newer?)");
  m.frame = Image::zeroed(width, height);
  m.make_current();
  m.disc_program = link(kDiscVert, kDiscFrag, "disc");
  m.segment_program = link(kSegmentVert, kSegmentFrag, "segment");
  glGenVertexArrays(1, &m.vao);
  glGenBuffers(5, m.disc_buffers);
  glGenBuffers(1, &m.quad_corner_buffer);
  glGenBuffers(1, &m.segment_buffer);
  glEnable(GL_PROGRAM_POINT_SIZE);
  glEnable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);  // premultiplied alpha
}

GlRenderer::~GlRenderer() {
  if (impl_ && impl_->context) OSMesaDestroyContext(impl_->context);
}

Image& GlRenderer::draw(const View& view, const DiscBatch& discs,
                        const std::vector<SegmentLine>& walls, const DrawStyle& style) {
  auto& m = *impl_;
  m.make_current();
  // The frame and a guard band around it; the band is outside the colour buffer.
  const int viewport_w = width_ + 2 * kGuard, viewport_h = height_ + 2 * kGuard;
  glViewport(-kGuard, -kGuard, viewport_w, viewport_h);
  const float a = style.background.a / 255.0f;
  glClearColor(style.background.r / 255.0f * a, style.background.g / 255.0f * a,
               style.background.b / 255.0f * a, a);
  // A movie's frames share their view, walls and style; llvmpipe clears a whole 1280x720 frame
  // in ~1 ms, most of it background that stays (docs/performance_log.md, issue 12, ninth session).
  const PixelRect now = disc_pixels(view, discs, width_, height_);
  const bool like_last = m.drawn && view == m.last_view && style == m.last_style && walls == m.last_walls &&
                         method_ == m.last_method;
  const PixelRect changed = now.joined(m.last_discs);
  const bool partial = like_last && !changed.empty();
  if (partial) {
    glEnable(GL_SCISSOR_TEST);
    glScissor(changed.x0, changed.y0, changed.x1 - changed.x0, changed.y1 - changed.y0);
  }
  glClear(GL_COLOR_BUFFER_BIT);
  glBindVertexArray(m.vao);

  // World point at the viewport's lower-left pixel, guard band included.
  const float origin[2] = {static_cast<float>(view.x0 - kGuard / view.scale),
                           static_cast<float>(view.y0 - kGuard / view.scale)};
  const float viewport[2] = {static_cast<float>(viewport_w), static_cast<float>(viewport_h)};
  const float scale = static_cast<float>(view.scale);

  // ---- walls ----
  if (!walls.empty()) {
    const double hw = style.wall_half_width_px, margin = hw + 1.0;
    m.scratch.clear();
    for (const auto& s : walls) {
      double dx = s.bx - s.ax, dy = s.by - s.ay;
      const double len = std::hypot(dx, dy);
      if (len <= 0) continue;
      dx /= len; dy /= len;
      const double ex = dx * hw / view.scale, ey = dy * hw / view.scale;  // square caps
      const double nx = -dy * margin / view.scale, ny = dx * margin / view.scale;
      const double ax = s.ax - ex, ay = s.ay - ey, bx = s.bx + ex, by = s.by + ey;
      const double v[6][3] = {{ax + nx, ay + ny, margin}, {ax - nx, ay - ny, -margin}, {bx + nx, by + ny, margin},
                              {bx + nx, by + ny, margin}, {ax - nx, ay - ny, -margin}, {bx - nx, by - ny, -margin}};
      for (const auto& p : v)
        for (double c : p) m.scratch.push_back(static_cast<float>(c));
    }
    glUseProgram(m.segment_program);
    glUniform2fv(glGetUniformLocation(m.segment_program, "u_origin"), 1, origin);
    glUniform1f(glGetUniformLocation(m.segment_program, "u_scale"), scale);
    glUniform2fv(glGetUniformLocation(m.segment_program, "u_viewport"), 1, viewport);
    glUniform1f(glGetUniformLocation(m.segment_program, "u_half_width_px"), static_cast<float>(hw));
    glUniform4f(glGetUniformLocation(m.segment_program, "u_colour"), style.wall.r / 255.0f,
                style.wall.g / 255.0f, style.wall.b / 255.0f, style.wall.a / 255.0f);
    for (GLuint k = 0; k < 5; ++k) glDisableVertexAttribArray(k);
    glBindBuffer(GL_ARRAY_BUFFER, m.segment_buffer);
    glBufferData(GL_ARRAY_BUFFER, m.scratch.size() * sizeof(float), m.scratch.data(), GL_STREAM_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 3 * sizeof(float), nullptr);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 1, GL_FLOAT, GL_FALSE, 3 * sizeof(float), reinterpret_cast<void*>(2 * sizeof(float)));
    glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(m.scratch.size() / 3));
  }

  // ---- discs ----
  if (discs.size() > 0) {
    glUseProgram(m.disc_program);
    glUniform2fv(glGetUniformLocation(m.disc_program, "u_origin"), 1, origin);
    glUniform1f(glGetUniformLocation(m.disc_program, "u_scale"), scale);
    glUniform2fv(glGetUniformLocation(m.disc_program, "u_viewport"), 1, viewport);
    glUniform1f(glGetUniformLocation(m.disc_program, "u_outline_px"), static_cast<float>(style.outline_px));
    glUniform1i(glGetUniformLocation(m.disc_program, "u_spokes"), style.spokes ? 1 : 0);
    glUniform3f(glGetUniformLocation(m.disc_program, "u_ink"), style.ink.r / 255.0f, style.ink.g / 255.0f,
                style.ink.b / 255.0f);
    float max_radius = 0;
    for (float r : discs.radius) max_radius = std::max(max_radius, r);
    const bool sprites = method_ == DiscMethod::point_sprites &&
                         2.0f * (max_radius * scale + 1.0f) <= kMaxPointSize;
    glUniform1i(glGetUniformLocation(m.disc_program, "u_sprites"), sprites ? 1 : 0);
    const std::size_t n = discs.size();
    const int repeat = sprites ? 1 : 6;  // a quad is two triangles
    auto upload = [&](GLuint index, GLuint buffer, const void* data, std::size_t bytes_per, int comps,
                      GLenum type, GLboolean normalise) {
      glBindBuffer(GL_ARRAY_BUFFER, buffer);
      if (repeat == 1) {
        glBufferData(GL_ARRAY_BUFFER, n * bytes_per, data, GL_STREAM_DRAW);
      } else {
        std::vector<std::uint8_t> expanded(n * bytes_per * repeat);
        const auto* src = static_cast<const std::uint8_t*>(data);
        for (std::size_t k = 0; k < n; ++k)
          for (int r = 0; r < repeat; ++r) std::memcpy(&expanded[(k * repeat + r) * bytes_per], &src[k * bytes_per], bytes_per);
        glBufferData(GL_ARRAY_BUFFER, expanded.size(), expanded.data(), GL_STREAM_DRAW);
      }
      glEnableVertexAttribArray(index);
      glVertexAttribPointer(index, comps, type, normalise, 0, nullptr);
    };
    m.scratch.resize(2 * n);
    for (std::size_t k = 0; k < n; ++k) { m.scratch[2 * k] = discs.x[k]; m.scratch[2 * k + 1] = discs.y[k]; }
    upload(0, m.disc_buffers[0], m.scratch.data(), 2 * sizeof(float), 2, GL_FLOAT, GL_FALSE);
    upload(1, m.disc_buffers[1], discs.radius.data(), sizeof(float), 1, GL_FLOAT, GL_FALSE);
    upload(2, m.disc_buffers[2], discs.colour.data(), 4, 4, GL_UNSIGNED_BYTE, GL_TRUE);
    upload(3, m.disc_buffers[3], discs.angle.data(), sizeof(float), 1, GL_FLOAT, GL_FALSE);
    if (sprites) {
      glDisableVertexAttribArray(4);
      glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(n));
    } else {
      static constexpr float kCorners[12] = {-1, -1, 1, -1, 1, 1, -1, -1, 1, 1, -1, 1};
      std::vector<float> corners(12 * n);
      for (std::size_t k = 0; k < n; ++k) std::memcpy(&corners[12 * k], kCorners, sizeof kCorners);
      glBindBuffer(GL_ARRAY_BUFFER, m.quad_corner_buffer);
      glBufferData(GL_ARRAY_BUFFER, corners.size() * sizeof(float), corners.data(), GL_STREAM_DRAW);
      glEnableVertexAttribArray(4);
      glVertexAttribPointer(4, 2, GL_FLOAT, GL_FALSE, 0, nullptr);
      glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(6 * n));
    }
  }
  if (partial) glDisable(GL_SCISSOR_TEST);
  glFinish();  // OSMesa copies the frame into `frame` here
  m.drawn = false;  // until this frame is known to be whole
  if (const GLenum err = glGetError(); err != GL_NO_ERROR)
    throw RenderError("OpenGL error " + std::to_string(err) + " while drawing a frame");
  m.drawn = true;
  m.last_view = view;
  m.last_style = style;
  if (!like_last) m.last_walls = walls;
  m.last_method = method_;
  m.last_discs = now;
  if (style.background.a < 255) unpremultiply(m.frame);
  return m.frame;
}

}  // namespace runout::render

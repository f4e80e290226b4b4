#include "runout/render/text.hpp"

#include <ft2build.h>
#include FT_FREETYPE_H

#include <cstdlib>

#include "runout/render/gl_renderer.hpp"

namespace runout::render {

namespace {

// Decodes UTF-8; malformed bytes become U+FFFD.
std::vector<char32_t> decode_utf8(std::string_view s) {
  std::vector<char32_t> out;
  for (std::size_t i = 0; i < s.size();) {
    const auto c = static_cast<unsigned char>(s[i]);
    int extra = c < 0x80 ? 0 : (c >> 5) == 6 ? 1 : (c >> 4) == 14 ? 2 : (c >> 3) == 30 ? 3 : -1;
    if (extra < 0 || i + extra >= s.size() + (extra == 0 ? 1 : 0)) { out.push_back(0xFFFD); ++i; continue; }
    char32_t code = extra == 0 ? c : c & (0x3F >> extra);
    for (int k = 1; k <= extra; ++k) code = (code << 6) | (static_cast<unsigned char>(s[i + k]) & 0x3F);
    out.push_back(code);
    i += extra + 1;
  }
  return out;
}

}  // namespace

std::string default_font_path() {
  if (const char* f = std::getenv("RUNOUT_FONT"); f && *f) return f;
  return "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
}

struct TextRenderer::Face {
  FT_Library library = nullptr;
  FT_Face face = nullptr;
  ~Face() {
    if (face) FT_Done_Face(face);
    if (library) FT_Done_FreeType(library);
  }
};

TextRenderer::TextRenderer(const std::string& font_path) : face_(std::make_unique<Face>()) {
  if (FT_Init_FreeType(&face_->library)) throw RenderError("FreeType: cannot initialise");
  if (FT_New_Face(face_->library, font_path.c_str(), 0, &face_->face))
    throw RenderError("font " + font_path +
                      " cannot be loaded (install fonts-dejavu-core or set RUNOUT_FONT)");
}

TextRenderer::~TextRenderer() = default;

const TextRenderer::Glyph& TextRenderer::glyph(char32_t code, int pixel_size) {
  const auto key = std::make_pair(code, pixel_size);
  if (auto it = cache_.find(key); it != cache_.end()) return it->second;
  Glyph g;
  FT_Set_Pixel_Sizes(face_->face, 0, static_cast<FT_UInt>(pixel_size));
  if (FT_Load_Char(face_->face, code, FT_LOAD_RENDER) == 0) {
    const FT_GlyphSlot s = face_->face->glyph;
    g.width = static_cast<int>(s->bitmap.width);
    g.height = static_cast<int>(s->bitmap.rows);
    g.left = s->bitmap_left;
    g.top = s->bitmap_top;
    g.advance = static_cast<int>(s->advance.x >> 6);
    g.coverage.resize(static_cast<std::size_t>(g.width) * g.height);
    for (int y = 0; y < g.height; ++y)
      for (int x = 0; x < g.width; ++x)
        g.coverage[static_cast<std::size_t>(y) * g.width + x] = s->bitmap.buffer[y * s->bitmap.pitch + x];
  }
  return cache_.emplace(key, std::move(g)).first->second;
}

int TextRenderer::draw(Image& image, int x, int y, std::string_view utf8, int pixel_size, Rgba colour) {
  int pen = x;
  for (char32_t c : decode_utf8(utf8)) {
    const Glyph& g = glyph(c, pixel_size);
    for (int gy = 0; gy < g.height; ++gy)
      for (int gx = 0; gx < g.width; ++gx) {
        const int cov = g.coverage[static_cast<std::size_t>(gy) * g.width + gx];
        if (cov) image.blend_coverage(pen + g.left + gx, y - g.top + gy, colour, cov);
      }
    pen += g.advance;
  }
  return pen - x;
}

int TextRenderer::width(std::string_view utf8, int pixel_size) {
  int w = 0;
  for (char32_t c : decode_utf8(utf8)) w += glyph(c, pixel_size).advance;
  return w;
}

int TextRenderer::ascent(int pixel_size) {
  FT_Set_Pixel_Sizes(face_->face, 0, static_cast<FT_UInt>(pixel_size));
  return static_cast<int>(face_->face->size->metrics.ascender >> 6);
}

}  // namespace runout::render

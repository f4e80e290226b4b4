// Text on frames through FreeType with a packaged DejaVu font, blended on the CPU after the
// OpenGL read-back (labels, colour bars, the t* stamp).
#pragma once

#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "runout/render/image.hpp"

namespace runout::render {

// $RUNOUT_FONT if set, else Debian's DejaVu Sans (package fonts-dejavu-core).
std::string default_font_path();

class TextRenderer {
 public:
  // Throws RenderError naming the font file if it cannot be loaded.
  explicit TextRenderer(const std::string& font_path = default_font_path());
  ~TextRenderer();
  TextRenderer(const TextRenderer&) = delete;
  TextRenderer& operator=(const TextRenderer&) = delete;

  // Draws UTF-8 text with the left end of its baseline at pixel (x, y); returns its width.
  int draw(Image& image, int x, int y, std::string_view utf8, int pixel_size, Rgba colour);
  int width(std::string_view utf8, int pixel_size);
  int ascent(int pixel_size);  // above the baseline, pixels

 private:
  struct Glyph {
    int width = 0, height = 0, left = 0, top = 0, advance = 0;
    std::vector<std::uint8_t> coverage;
  };
  const Glyph& glyph(char32_t code, int pixel_size);
  struct Face;
  std::unique_ptr<Face> face_;
  std::map<std::pair<char32_t, int>, Glyph> cache_;
};

}  // namespace runout::render

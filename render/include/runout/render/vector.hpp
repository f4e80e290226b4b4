// A frame as a vector picture: PDF through cairo, SVG written as XML. Discs are circles, walls
// lines, text stays text (DejaVu Sans), so the file scales and its labels can be searched and
// edited; the same plan and style as the OpenGL frame, so the two agree pixel for pixel up to
// anti-aliasing (tests/vector_snapshot_test.sh).
#pragma once

#include <functional>
#include <string>

#include "runout/render/canvas.hpp"
#include "runout/render/frame.hpp"

namespace runout::render {

// The file's bytes: background (unless transparent), walls, discs (outlines, spokes), then
// whatever `overlays` draws on the canvas. The page is width x height (PDF points, SVG user
// units), one unit per pixel of the PNG. Throws RenderError if cairo fails.
std::string encode_vector(PictureFormat format, int width, int height, const FramePlan& plan,
                          const DrawStyle& style, const std::function<void(Canvas&)>& overlays);

}  // namespace runout::render

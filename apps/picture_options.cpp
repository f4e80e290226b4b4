// Picture options are known to every build, so a build without the renderer can refuse them
// by name instead of misreading them.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "cli_checks.hpp"
#include "pictures.hpp"
#include "runout/errors.hpp"

namespace runout::app {

void add_picture_options(CLI::App* cmd, PictureOptions& o, bool with_movie) {
  if (with_movie) {
    cmd->add_option("--movie", o.movie, "write a video of the flow (.mp4: H.264 yuv420p; .mkv also works)");
    cmd->add_option("--frames", o.frames_dir, "write the movie frames as a PNG sequence into this folder");
    cmd->add_option("--snapshots", o.snapshots, "PNG snapshots at these t*, e.g. 0,20,40,60,80,100,250");
    cmd->add_option("--snapshot-dir", o.snapshot_dir, "folder for snapshots (default: --out)");
    cmd->add_option("--fps", o.fps, "movie frames per second")->check(CLI::Range(1, 240));
    cmd->add_option("--frame-every", o.frame_every, "t* between movie frames")->check(real_in(1e-3, 1e6));
    cmd->add_option("--crf", o.crf, "H.264 quality, 0..51 (lower is better)")->check(CLI::Range(0, 51));
    cmd->add_option("--preset", o.preset, "x264 preset (ultrafast .. veryslow)");
    cmd->add_flag("--lossless", o.lossless, "lossless H.264 (yuv444p, qp 0; not playable in browsers)");
  }
  cmd->add_option("--color", o.color, "species | spin | layer | speed")
      ->check(CLI::IsMember({"species", "spin", "layer", "speed"}));
  cmd->add_option("--camera", o.camera, "whole | front | deposit | window")
      ->check(CLI::IsMember({"whole", "front", "deposit", "window"}));
  cmd->add_option("--window", o.window, "x0,y0,x1,y1 in metres, for --camera window");
  cmd->add_option("--size", o.size, "frame size WxH in pixels (odd sizes are rounded up; H = 0: from the camera)");
  cmd->add_option("--front-width", o.front_width, "front camera: window width in D")->check(real_in(1.0, 1e5));
  cmd->add_option("--spin-limit", o.spin_limit, "spin colours saturate at +-this omega sqrt(d/g)")
      ->check(real_in(1e-6, 1e6));
  cmd->add_option("--speed-limit", o.speed_limit, "speed colours saturate at this |v|/sqrt(g d) (0: free-fall speed)")
      ->check(real_in(0.0, 1e6));
  cmd->add_flag("--spokes", o.spokes, "draw a spoke showing each disc's rotation");
  cmd->add_flag("--outlines", o.outlines, "draw a thin darker rim on each disc");
  cmd->add_flag("--transparent", o.transparent, "PNG with a transparent background");
  cmd->add_flag("--no-overlays", o.no_overlays, "no legend, colour bar, t* stamp or scale bar");
  cmd->add_flag("--quads", o.sprites_off, "draw discs as quads instead of point sprites");
}

FrameSize parse_frame_size(const std::string& text) {
  int w = 0, h = 0;
  char x = 0;
  std::istringstream in(text);
  if (!(in >> w >> x >> h) || x != 'x' || w < 16 || (h < 16 && h != 0) || w > 8192 || h > 8192 || !in.eof())
    throw UsageError("--size: \"" + text + "\" is not WxH with 16 <= W <= 8192 and 16 <= H <= 8192, or H = 0 "
                     "(the height from the camera's aspect)");
  return {w, h};
}

std::array<double, 4> parse_window(const std::string& text) {
  std::array<double, 4> v{};
  char c1 = 0, c2 = 0, c3 = 0;
  std::istringstream win(text);
  if (!(win >> v[0] >> c1 >> v[1] >> c2 >> v[2] >> c3 >> v[3]) || c1 != ',' || c2 != ',' || c3 != ',' ||
      !win.eof() || !std::all_of(v.begin(), v.end(), [](double a) { return std::isfinite(a); }) ||
      v[2] <= v[0] || v[3] <= v[1])
    throw UsageError("--window: \"" + text + "\" is not x0,y0,x1,y1 (m) with x1 > x0 and y1 > y0");
  return v;
}

std::vector<double> parse_times(const std::string& list, const std::string& option) {
  std::vector<double> out;
  std::stringstream ss(list);
  for (std::string item; std::getline(ss, item, ',');) {
    std::size_t used = 0;
    double v = 0;
    try {
      v = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != item.size() || !std::isfinite(v) || v < 0)
      throw UsageError(option + ": \"" + item + "\" is not a time t* >= 0");
    out.push_back(v);
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace runout::app

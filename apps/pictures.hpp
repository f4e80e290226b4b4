// Command-line options for pictures (runout run, runout render) and the commands that only
// exist with the renderer (render, compare). The binary defines them in picture_loader.cpp,
// each forwarding to its body in the picture module (picture_module.cpp, reached through
// PictureApi, picture_module.hpp).
#pragma once

#include <array>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "runout/observer.hpp"
#include "runout/scene.hpp"
#include "runout/setup.hpp"

namespace CLI { class App; }

namespace runout::app {

struct PictureOptions {
  std::string movie;         // video file (.mp4, .mkv)
  std::string frames_dir;    // PNG sequence folder
  std::string snapshots;     // "0,20,40"
  std::string snapshot_dir;  // default: the output folder
  std::string color = "species";
  std::string camera = "whole";
  std::string window;        // "x0,y0,x1,y1" (m), for --camera window
  std::string size = "1280x720";
  std::string snapshot_format;  // png, pdf or svg; empty: png (render: from the -o name)
  int fps = 30;
  double frame_every = 0.5;  // t* between movie frames
  int crf = 20;
  std::string preset = "ultrafast";
  bool lossless = false, spokes = false, outlines = false, transparent = false, no_overlays = false;
  double spin_limit = 10.0, speed_limit = 0.0, front_width = 50.0;
  bool sprites_off = false;  // draw discs as quads (for measuring both methods)

  bool wants_pictures() const { return !movie.empty() || !frames_dir.empty() || !snapshots.empty(); }
};

// Adds the frame options (colour, camera, size, style) to a subcommand; `with_movie` adds the
// movie, frames and snapshots options too.
void add_picture_options(CLI::App* cmd, PictureOptions& o, bool with_movie);

// Parses "0,20,40" into sorted times; throws UsageError naming the option and the bad item.
std::vector<double> parse_times(const std::string& list, const std::string& option = "--snapshots");
// "1280x720" (16..8192 each; odd sizes are rounded up later, for video) and "x0,y0,x1,y1";
// both throw UsageError naming the option.
struct FrameSize { int width = 0, height = 0; };
FrameSize parse_frame_size(const std::string& text);
std::array<double, 4> parse_window(const std::string& text);

struct RenderOptions {
  std::string checkpoint;
  std::string scene;  // default: scene.resolved.toml beside the checkpoint
  std::string output;
  PictureOptions picture;
  // If set, a JSON file beside the picture says what it shows: t*, the world window it covers
  // (extent, metres) and the legend's colours and labels (for figures that draw their own axes).
  std::string describe;
  bool quiet = false;
};
struct CompareOptions {
  std::string expected, actual, diff;
  int tolerance = 24;
  double max_share = 0.002;
};

int render_command(const RenderOptions& o);
int compare_command(const CompareOptions& o);

// The movie and snapshot observers of one run; the run command attaches them.
class PictureSession {
 public:
  virtual ~PictureSession() = default;
  // Each observer with when it fires; they live as long as the session.
  virtual std::vector<std::pair<Observer*, Schedule>> observers() = 0;
  virtual double last_time() const = 0;   // t* of the last snapshot (0: none): the run goes on to it
  virtual void finish() = 0;              // completes the video
  virtual std::string report() const = 0; // what was written, for stderr
};
// Throws (std::exception) on bad options or when the renderer cannot start. `world` is the
// state the run starts from: the whole camera is decided on it, and a frame height of 0 sized.
std::unique_ptr<PictureSession> open_pictures(const PictureOptions& o, const World& world, const SceneDef& scene,
                                              const SceneSetup& setup, const std::string& out_dir);
// `runout bench --frames N`: times drawing (+ read-back), PNG encoding and video encoding of
// N frames of `world`, advancing it `steps_between` steps between frames; prints ms per frame.
int bench_frames(World& world, const SceneDef& scene, const SceneSetup& setup, const PictureOptions& o,
                 long long frames, long long steps_between);

}  // namespace runout::app

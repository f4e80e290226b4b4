// The picture module (runout_pictures.so): everything that draws, behind PictureApi.
#include "pictures.hpp"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "picture_module.hpp"
#include "runout/checkpoint.hpp"
#include "runout/errors.hpp"
#include "runout/io/files.hpp"
#include "runout/io/scene_file.hpp"
#include "runout/render/colormap.hpp"
#include "runout/render/recorders.hpp"
#include "runout/render/vector.hpp"
#include "runout/setup.hpp"
#include "runout/timing.hpp"

namespace runout::app {

namespace {

render::FrameOptions frame_options(const PictureOptions& o) {
  render::FrameOptions f;
  auto [w, h] = parse_frame_size(o.size);  // h = 0: from the camera (FrameMaker)
  if (w % 2 || h % 2) {
    std::fprintf(stderr, "runout: note: --size %dx%d rounded up to %dx%d (video needs even sizes)\n", w, h,
                 w + w % 2, h + h % 2);
    w += w % 2;
    h += h % 2;
  }
  f.width = w;
  f.height = h;
  f.color = render::parse_color_mode(o.color);
  f.camera = render::parse_camera_mode(o.camera);
  if (f.camera == render::CameraMode::window) {
    const auto v = parse_window(o.window);
    for (int k = 0; k < 4; ++k) f.window[k] = v[k];
  }
  f.front_width = o.front_width;
  f.spokes = o.spokes;
  f.outlines = o.outlines;
  f.transparent = o.transparent;
  f.overlays = !o.no_overlays;
  f.spin_limit = o.spin_limit;
  f.speed_limit = o.speed_limit;
  f.method = o.sprites_off ? render::DiscMethod::quads : render::DiscMethod::point_sprites;
  return f;
}

class Session : public PictureSession {
 public:
  Session(const PictureOptions& o, const World& world, const SceneDef& scene, const SceneSetup& setup,
          const std::string& out_dir) {
    const render::FrameOptions frame = frame_options(o);
    if (!o.movie.empty() || !o.frames_dir.empty()) {
      render::VideoOptions video;
      video.fps = o.fps;
      video.crf = o.crf;
      video.preset = o.preset;
      video.lossless = o.lossless;
      movie_.emplace(frame, scene, setup, world, o.movie, video, o.frames_dir);
      observers_.push_back({&*movie_, {o.frame_every, 0.0, {}}});
      movie_path_ = o.movie;
    }
    if (!o.snapshots.empty()) {
      const auto times = parse_times(o.snapshots);
      snapshots_.emplace(frame, scene, setup, world, o.snapshot_dir.empty() ? out_dir : o.snapshot_dir, times,
                         render::parse_picture_format(o.snapshot_format.empty() ? "png" : o.snapshot_format));
      observers_.push_back({&*snapshots_, {0.0, 0.0, times}});
      last_time_ = times.back();
    }
  }
  std::vector<std::pair<Observer*, Schedule>> observers() override { return observers_; }
  double last_time() const override { return last_time_; }
  void finish() override {
    if (movie_) movie_->finish();
  }
  std::string report() const override {
    std::ostringstream r;
    if (movie_) {
      r << movie_->frames() << " movie frames";
      if (!movie_path_.empty()) r << " in " << movie_path_;
    }
    if (snapshots_) r << (movie_ ? "; " : "") << snapshots_->written().size() << " snapshots";
    return r.str();
  }

 private:
  std::optional<render::MovieRecorder> movie_;
  std::optional<render::SnapshotWriter> snapshots_;
  std::string movie_path_;
  std::vector<std::pair<Observer*, Schedule>> observers_;
  double last_time_ = 0;
};

// The module's bodies of the commands pictures.hpp declares, under their own names (the binary's definitions in
// picture_loader.cpp forward to these through PictureApi).
std::unique_ptr<PictureSession> module_open(const PictureOptions& o, const World& world, const SceneDef& scene,
                                            const SceneSetup& setup, const std::string& out_dir) {
  return std::make_unique<Session>(o, world, scene, setup, out_dir);
}

// --snapshot-format if given, else the -o name's extension (.pdf, .svg), else PNG. A format
// that contradicts the name's extension is refused: a PDF named f.png helps no one.
render::PictureFormat render_format(const RenderOptions& o) {
  std::string ext = std::filesystem::path(o.output).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  const bool known = ext == ".png" || ext == ".pdf" || ext == ".svg";
  if (o.picture.snapshot_format.empty()) return render::parse_picture_format(known ? ext.substr(1) : "png");
  if (known && ext.substr(1) != o.picture.snapshot_format)
    throw UsageError("--snapshot-format " + o.picture.snapshot_format + " but -o " + o.output + " names a " +
                     ext.substr(1) + " file");
  return render::parse_picture_format(o.picture.snapshot_format);
}

int module_render(const RenderOptions& o) {
  const render::PictureFormat format = render_format(o);
  // Default: the run's scene beside the checkpoint, or one folder up for OUT/states/*.bin.
  std::string scene_path = o.scene;
  if (scene_path.empty()) {
    const std::filesystem::path dir = std::filesystem::path(o.checkpoint).parent_path();
    scene_path = (dir / "scene.resolved.toml").string();
    if (!std::filesystem::exists(scene_path) && std::filesystem::exists(dir.parent_path() / "scene.resolved.toml"))
      scene_path = (dir.parent_path() / "scene.resolved.toml").string();
  }
  const SceneDef scene = io::read_scene_file(scene_path);
  const SceneSetup setup = derive_setup(scene, scene_path);
  World world = build_explicit_world(scene, setup, 1);
  const std::string bytes = io::read_regular_file(o.checkpoint, UINTMAX_MAX);  // not a FIFO or device
  decode_checkpoint(bytes, io::physics_key(scene), world, o.checkpoint);
  const double t_star = world.time() / setup.unit_time;
  const render::FrameOptions frame = frame_options(o.picture);
  render::FrameMaker maker(frame, scene, setup, &world);
  render::write_picture(o.output, maker, world, t_star, format);
  if (!o.describe.empty()) {
    const render::View& v = maker.view();
    const int W = maker.options().width, H = maker.options().height;
    nlohmann::json j;
    j["t_star"] = t_star;
    j["width"] = W;
    j["height"] = H;
    j["extent"] = {v.x0, v.x0 + W / v.scale, v.y0, v.y0 + H / v.scale};
    j["legend"] = nlohmann::json::array();
    for (const auto& [c, label] : maker.legend_entries()) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "#%02x%02x%02x", c.r, c.g, c.b);
      j["legend"].push_back({{"label", label}, {"color", hex}});
    }
    io::write_file_atomically(o.describe, j.dump(1) + "\n");
  }
  if (!o.quiet) std::fprintf(stderr, "runout: wrote %s (t* = %.2f)\n", o.output.c_str(), t_star);
  return 0;
}

int module_bench(World& world, const SceneDef& scene, const SceneSetup& setup, const PictureOptions& o,
                 long long frames, long long steps_between) {
  render::FrameMaker maker(frame_options(o), scene, setup, &world);
  const render::FrameOptions& frame = maker.options();
  std::vector<render::Image> images;
  double draw = 0, png = 0;
  std::size_t png_bytes = 0;
  for (long long f = 0; f < frames; ++f) {
    world.advance(steps_between);
    auto t0 = Clock::now();
    const render::Image& img = maker.make(world, world.time() / setup.unit_time);
    draw += seconds_since(t0);
    t0 = Clock::now();
    png_bytes += render::encode_png(img, false).size();
    png += seconds_since(t0);
    images.push_back(img);  // kept for the video stage below, untimed: a movie keeps no frames
  }
  // Video encoding alone, frames fed as fast as the encoder takes them.
  const std::string video_path = (std::filesystem::temp_directory_path() / "runout_bench.mp4").string();
  render::VideoOptions video;
  video.preset = o.preset;
  video.crf = o.crf;
  video.lossless = o.lossless;
  auto t0 = Clock::now();
  {
    render::VideoWriter writer(video_path, frame.width, frame.height, video);
    for (auto& img : images) writer.write(img);
    writer.finish();
  }
  const double encode = seconds_since(t0);
  std::filesystem::remove(video_path);
  const double n = static_cast<double>(frames);
  std::printf("frame_size: %dx%d\n", frame.width, frame.height);
  std::printf("disc_method: %s\n", frame.method == render::DiscMethod::quads ? "quads" : "point_sprites");
  std::printf("discs: %zu\n", world.particles().size());
  std::printf("frames: %lld\n", frames);
  std::printf("draw_readback_overlays_ms: %.2f\n", 1000 * draw / n);
  std::printf("png_encode_ms: %.2f\n", 1000 * png / n);
  std::printf("png_kib: %.1f\n", png_bytes / n / 1024.0);
  std::printf("video_encode_ms: %.2f\n", 1000 * encode / n);
  std::printf("draw_plus_png_ms: %.2f\n", 1000 * (draw + png) / n);
  std::printf("draw_plus_video_ms: %.2f\n", 1000 * (draw + encode) / n);
  return 0;
}

int module_compare(const CompareOptions& o) {
  // Exit codes: 0 match, 1 no match, 2 bad input (an unreadable PNG, a --diff that cannot be
  // written) — the last checked before anything is compared, so 1 always means "differ".
  if (!o.diff.empty()) {
    const std::filesystem::path d(o.diff);
    const std::filesystem::path folder = d.has_parent_path() ? d.parent_path() : ".";
    std::error_code ec;
    if (std::filesystem::is_directory(d, ec) || !std::filesystem::is_directory(folder, ec) ||
        ::access(folder.c_str(), W_OK | X_OK) != 0) {
      std::fprintf(stderr, "runout compare: --diff: cannot write %s (no such writable folder, or it is a folder)\n",
                   o.diff.c_str());
      return 2;
    }
  }
  render::Image expected, actual;
  try {
    expected = render::read_png(o.expected);
    actual = render::read_png(o.actual);
  } catch (const IoError& e) {
    std::fprintf(stderr, "runout compare: %s\n", e.what());
    return 2;
  }
  render::CompareOptions opts;
  opts.pixel_threshold = o.tolerance;
  opts.max_share = o.max_share;
  const render::Comparison c = render::compare_images(expected, actual, opts);
  if (!c.same_size) {
    std::fprintf(stderr, "runout compare: sizes differ: %dx%d vs %dx%d\n", expected.width, expected.height,
                 actual.width, actual.height);
    return 1;
  }
  std::printf("differing_pixels: %ld\nshare: %.6f\nrms: %.3f\nmax_difference: %d\nmatch: %s\n",
              c.differing_pixels, c.share, c.rms, c.max_difference, c.match ? "yes" : "no");
  if (!o.diff.empty()) {
    try {
      render::write_png(o.diff, c.diff);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "runout compare: --diff: %s\n", e.what());
      return 2;
    }
  }
  return c.match ? 0 : 1;
}

}  // namespace

}  // namespace runout::app

extern "C" __attribute__((visibility("default"))) const runout::app::PictureApi* runout_picture_api() {
  using namespace runout::app;
  static const PictureApi api = [] {
    PictureApi a = expected_picture_api_layout(RUNOUT_BUILD_STAMP);
    a.render = &module_render;
    a.compare = &module_compare;
    a.open = &module_open;
    a.bench = &module_bench;
    return a;
  }();
  return &api;
}

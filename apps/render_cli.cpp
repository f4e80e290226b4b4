// The picture module (runout_pictures.so): everything that draws, behind PictureApi.
#include "render_cli.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <unistd.h>

#include "picture_module.hpp"
#include "runout/checkpoint.hpp"
#include "runout/errors.hpp"
#include "runout/io/files.hpp"
#include "runout/io/scene_file.hpp"
#include "runout/render/colormap.hpp"
#include "runout/render/recorders.hpp"
#include "runout/setup.hpp"

namespace runout::app {

namespace {

render::FrameOptions frame_options(const PictureOptions& o) {
  render::FrameOptions f;
  auto [w, h] = parse_frame_size(o.size);
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
  Session(const PictureOptions& o, AvalancheRun& run, const SceneDef& scene, const SceneSetup& setup,
          const std::string& out_dir) {
    const render::FrameOptions frame = frame_options(o);
    if (!o.movie.empty() || !o.frames_dir.empty()) {
      render::VideoOptions video;
      video.fps = o.fps;
      video.crf = o.crf;
      video.preset = o.preset;
      video.lossless = o.lossless;
      movie_.emplace(frame, scene, setup, o.movie, video, o.frames_dir);
      run.add_observer(*movie_, {o.frame_every, 0.0, {}});
      movie_path_ = o.movie;
    }
    if (!o.snapshots.empty()) {
      const auto times = parse_times(o.snapshots);
      snapshots_.emplace(frame, scene, setup, o.snapshot_dir.empty() ? out_dir : o.snapshot_dir, times);
      run.add_observer(*snapshots_, {0.0, 0.0, times});
      run.set_min_end_time(times.back());  // the run goes on to the last snapshot
    }
  }
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
};

}  // namespace

std::unique_ptr<PictureSession> attach_pictures(const PictureOptions& o, AvalancheRun& run,
                                                const SceneDef& scene, const SceneSetup& setup,
                                                const std::string& out_dir) {
  return std::make_unique<Session>(o, run, scene, setup, out_dir);
}

int render_command(const RenderOptions& o) {
  const std::string scene_path =
      o.scene.empty() ? (std::filesystem::path(o.checkpoint).parent_path() / "scene.resolved.toml").string() : o.scene;
  const SceneDef scene = io::read_scene_file(scene_path);
  const SceneSetup setup = derive_setup(scene, scene_path);
  World world = build_explicit_world(scene, setup, 1);
  const std::string bytes = io::read_regular_file(o.checkpoint, UINTMAX_MAX);  // not a FIFO or device
  decode_checkpoint(bytes, io::physics_key(scene), world, o.checkpoint);
  const double t_star = world.time() / setup.unit_time;
  render::FrameMaker maker(frame_options(o.picture), scene, setup);
  render::write_png(o.output, maker.make(world, t_star), o.picture.transparent);
  std::fprintf(stderr, "runout: wrote %s (t* = %.2f)\n", o.output.c_str(), t_star);
  return 0;
}

int bench_frames(World& world, const SceneDef& scene, const SceneSetup& setup, const PictureOptions& o,
                 long long frames, long long steps_between) {
  using Clock = std::chrono::steady_clock;
  const render::FrameOptions frame = frame_options(o);
  render::FrameMaker maker(frame, scene, setup);
  std::vector<render::Image> images;
  double draw = 0, png = 0;
  std::size_t png_bytes = 0;
  for (long long f = 0; f < frames; ++f) {
    for (long long s = 0; s < steps_between; ++s) world.step();
    auto t0 = Clock::now();
    render::Image img = maker.make(world, world.time() / setup.unit_time);
    draw += std::chrono::duration<double>(Clock::now() - t0).count();
    t0 = Clock::now();
    png_bytes += render::encode_png(img, false).size();
    png += std::chrono::duration<double>(Clock::now() - t0).count();
    images.push_back(std::move(img));
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
  const double encode = std::chrono::duration<double>(Clock::now() - t0).count();
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

void plot_study(const std::vector<StudyPoint>& points, const std::string& title, const std::string& path) {
  const int W = 1200, H = 640, left = 90, right = 330, top = 60, bottom = 70;
  render::Image img(W, H);
  render::TextRenderer text;
  const render::Rgba ink{30, 30, 30, 255}, grid{225, 225, 225, 255}, bar{120, 120, 120, 255};
  const auto noise_of = [](const StudyPoint& p) { return std::isfinite(p.noise) ? p.noise : 0.0; };
  double x0 = 1e300, x1 = 0, y0 = 1e300, y1 = 0;
  for (const auto& p : points) {
    if (!(p.seconds_per_t_star > 0)) throw std::invalid_argument("a study point has no positive cost");
    x0 = std::min(x0, p.seconds_per_t_star); x1 = std::max(x1, p.seconds_per_t_star);
    for (double y : {p.mu_error, p.mu_error + noise_of(p)})
      if (y > 0) { y0 = std::min(y0, y); y1 = std::max(y1, y); }
  }
  if (y1 <= 0) { y0 = 1e-4; y1 = 1e-1; }
  const double lx0 = std::floor(std::log10(x0) - 0.15), lx1 = std::ceil(std::log10(x1) + 1e-9);
  const double ly0 = std::floor(std::log10(y0) - 0.3), ly1 = std::ceil(std::log10(y1) + 1e-9);
  auto px = [&](double x) { return left + (std::log10(x) - lx0) / std::max(lx1 - lx0, 1.0) * (W - left - right); };
  auto py = [&](double y) {
    if (!(y > 0)) return double(H - bottom - 4);  // zero: drawn on the axis
    return std::max(double(top), H - bottom - (std::log10(y) - ly0) / std::max(ly1 - ly0, 1.0) * (H - top - bottom));
  };
  for (double d = lx0; d <= lx1; ++d) {
    const int x = static_cast<int>(px(std::pow(10, d)));
    img.fill_rect(x, top, x + 1, H - bottom, grid);
    char l[16]; std::snprintf(l, sizeof l, "%g", std::pow(10, d));
    text.draw(img, x - text.width(l, 14) / 2, H - bottom + 20, l, 14, ink);
  }
  for (double d = ly0; d <= ly1; ++d) {
    const int y = static_cast<int>(py(std::pow(10, d)));
    img.fill_rect(left, y, W - right, y + 1, grid);
    char l[16]; std::snprintf(l, sizeof l, "%g", std::pow(10, d));
    text.draw(img, left - 8 - text.width(l, 14), y + 5, l, 14, ink);
  }
  img.fill_rect(left, H - bottom, W - right, H - bottom + 2, ink);
  img.fill_rect(left - 2, top, left, H - bottom, ink);
  text.draw(img, (W - text.width(title, 18)) / 2, 28, title, 18, ink);
  const std::string xl = "wall seconds per t* of flow (runs end at different t*), mean over the piles";
  const std::string yl = "|mean mu - mean mu of the reference|; bars: +- 2 standard errors (0 on the axis)";
  text.draw(img, left + ((W - left - right) - text.width(xl, 15)) / 2, H - 20, xl, 15, ink);
  text.draw(img, left, top - 10, yl, 13, ink);
  // Points numbered on the plot, named in a legend on the right: labels never collide.
  int number = 0;
  for (const auto& p : points) {
    ++number;
    const double cx = px(p.seconds_per_t_star), cy = py(p.mu_error);
    const double n = noise_of(p);
    if (n > 0) {
      const int ya = static_cast<int>(py(p.mu_error + n)), yb = static_cast<int>(p.mu_error - n > 0 ? py(p.mu_error - n) : H - bottom);
      img.fill_rect(static_cast<int>(cx), ya, static_cast<int>(cx) + 1, yb, bar);
      img.fill_rect(static_cast<int>(cx) - 4, ya, static_cast<int>(cx) + 5, ya + 1, bar);
    }
    for (int y = static_cast<int>(cy) - 6; y <= cy + 6; ++y)
      for (int x = static_cast<int>(cx) - 6; x <= cx + 6; ++x)
        img.blend(x, y, render::palette::kLarge, std::clamp(5.0 - std::hypot(x + 0.5 - cx, y + 0.5 - cy) + 0.5, 0.0, 1.0));
    const std::string tag = std::to_string(number);
    text.draw(img, static_cast<int>(cx) + 8, static_cast<int>(cy) - 4, tag, 13, ink);
    text.draw(img, W - right + 16, top + 10 + 20 * number, tag + "  " + p.label, 13, ink);
  }
  render::write_png(path, img);
}

int compare_command(const CompareOptions& o) {
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

}  // namespace runout::app

extern "C" __attribute__((visibility("default"))) const runout::app::PictureApi* runout_picture_api() {
  using namespace runout::app;
  static const PictureApi api = [] {
    PictureApi a = expected_picture_api_layout(RUNOUT_BUILD_STAMP);
    a.render = &render_command;
    a.compare = &compare_command;
    a.attach = &attach_pictures;
    a.bench = &bench_frames;
    a.plot = &plot_study;
    return a;
  }();
  return &api;
}

#include "runout/render/recorders.hpp"

#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <limits>

#include "runout/io/files.hpp"
#include "runout/render/batch_worker.hpp"

namespace runout::render {

namespace {
// llvmpipe starts its rasteriser threads (LP_NUM_THREADS, default one per core) with the first
// OpenGL context. With 0 the drawing thread rasterises itself, beside the video encoder's
// thread on the other core. Read once per process; a value the user set is kept.
int draw_on_the_idle_thread() { return ::setenv("LP_NUM_THREADS", "0", /*overwrite=*/0); }
}  // namespace

MovieRecorder::MovieRecorder(const FrameOptions& frame, const SceneDef& scene, const SceneSetup& setup,
                             const World& first, const std::string& video_path, const VideoOptions& video,
                             const std::string& png_dir)
    : maker_((draw_on_the_idle_thread(), frame), scene, setup, &first), png_dir_(png_dir), keep_alpha_(frame.transparent) {
  if (!video_path.empty()) video_.emplace(video_path, maker_.options().width, maker_.options().height, video);
  if (!png_dir_.empty()) io::make_directories(png_dir_);
  // Nothing is drawn or encoded while the physics steps (observe opens them per batch).
  if (video_) video_->set_encoding(false);
  worker_ = std::make_unique<BatchWorker<FramePlan>>(/*open=*/false, [this](FramePlan& plan) { draw(plan); });
}

MovieRecorder::~MovieRecorder() = default;

// On the helper thread: the picture, then the PNG and the video.
void MovieRecorder::draw(const FramePlan& plan) {
  const Image& img = maker_.draw(plan);
  if (!png_dir_.empty()) {
    char name[48];
    std::snprintf(name, sizeof name, "/frame_%06ld.png", drawn_);
    write_png(png_dir_ + name, img, keep_alpha_);
  }
  if (video_) video_->write(img);
  ++drawn_;
}

void MovieRecorder::observe(const World& world, const RunState&, double t_star) {
  // Two batches behind (a scene that steps faster than frames are drawn): the simulation waits,
  // asleep on every physics thread, for room.
  if (worker_->queued() >= 2 * kBatch)
    wait_on_every_thread(world.settings().threads, [this] { worker_->wait_for_room(kBatch); });
  worker_->push(maker_.plan(world, t_star));
  ++frames_;
  if (drawing_ || worker_->queued() < kBatch) return;
  worker_->set_open(true);
  if (video_) video_->set_encoding(true);
  drawing_ = true;
}

int MovieRecorder::helper_cores() {
  if (!drawing_) return 0;
  if (!worker_->idle() || (video_ && !video_->encoded())) return 1;
  // The batch is drawn and encoded: the next waits until it is whole, and the core goes back.
  worker_->set_open(false);
  if (video_) video_->set_encoding(false);
  drawing_ = false;
  return 0;
}

void MovieRecorder::finish() {
  if (video_) video_->set_encoding(true);  // the last frames: drawn and encoded side by side
  worker_->finish();
  if (video_) video_->finish();
}

std::string snapshot_name(double t_star, PictureFormat format) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "snapshot_t%g.%s", t_star, extension(format));
  return buf;
}

void write_picture(const std::string& path, FrameMaker& maker, const World& world, double t_star,
                   PictureFormat format) {
  if (format == PictureFormat::png) write_png(path, maker.make(world, t_star), maker.options().transparent);
  else io::write_file_atomically(path, maker.make_vector(world, t_star, format));
}

SnapshotWriter::SnapshotWriter(const FrameOptions& frame, const SceneDef& scene, const SceneSetup& setup,
                               const World& first, std::string dir, std::vector<double> times,
                               PictureFormat format)
    : maker_(frame, scene, setup, &first), dir_(std::move(dir)), times_(std::move(times)), format_(format) {
  io::make_directories(dir_);
}

void SnapshotWriter::observe(const World& world, const RunState&, double t_star) {
  // The requested time this frame stands for: the nearest one.
  double requested = t_star, best = std::numeric_limits<double>::infinity();
  for (double t : times_)
    if (std::abs(t - t_star) < best) { best = std::abs(t - t_star); requested = t; }
  const std::string path = dir_ + "/" + snapshot_name(requested, format_);
  write_picture(path, maker_, world, t_star, format_);
  written_.push_back(path);
}

}  // namespace runout::render

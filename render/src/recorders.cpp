#include "runout/render/recorders.hpp"

#include <chrono>
#include <condition_variable>
#include <deque>
#include <mutex>
#include <thread>
#include <cmath>
#include <cstdio>
#include <limits>

#include "runout/io/files.hpp"
#include "runout/render/idle_thread.hpp"

namespace runout::render {

struct MovieRecorder::Worker {
  FrameMaker& maker;
  std::optional<VideoWriter> video;
  std::string png_dir;
  bool keep_alpha = false;
  std::mutex mutex;
  std::condition_variable changed;
  std::deque<FramePlan> queue;
  bool closing = false, done = false;
  std::exception_ptr error;
  double draw_seconds = 0;
  long drawn = 0;
  std::thread thread;

  explicit Worker(FrameMaker& m) : maker(m) {}

  void run() {
    run_when_idle();
    try {
      for (;;) {
        FramePlan plan;
        {
          std::unique_lock lock(mutex);
          changed.wait(lock, [&] { return !queue.empty() || closing; });
          if (queue.empty()) break;
          plan = std::move(queue.front());
          queue.pop_front();
        }
        changed.notify_all();
        const auto t0 = std::chrono::steady_clock::now();
        Image img = maker.draw(plan);
        if (!png_dir.empty()) {
          char name[48];
          std::snprintf(name, sizeof name, "/frame_%06ld.png", drawn);
          write_png(png_dir + name, img, keep_alpha);
        }
        draw_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        if (video) video->write(std::move(img));
        ++drawn;
      }
    } catch (...) {
      std::lock_guard lock(mutex);
      error = std::current_exception();
      queue.clear();
    }
    std::lock_guard lock(mutex);
    done = true;
    changed.notify_all();
  }
};

MovieRecorder::MovieRecorder(const FrameOptions& frame, const SceneDef& scene, const SceneSetup& setup,
                             const std::string& video_path, const VideoOptions& video,
                             const std::string& png_dir)
    : maker_(frame, scene, setup), worker_(std::make_unique<Worker>(maker_)) {
  if (!video_path.empty()) worker_->video.emplace(video_path, frame.width, frame.height, video);
  worker_->png_dir = png_dir;
  worker_->keep_alpha = frame.transparent;
  if (!png_dir.empty()) io::make_directories(png_dir);
  worker_->thread = std::thread([w = worker_.get()] { w->run(); });
}

MovieRecorder::~MovieRecorder() {
  if (worker_->thread.joinable()) {
    {
      std::lock_guard lock(worker_->mutex);
      worker_->queue.clear();
      worker_->closing = true;
    }
    worker_->changed.notify_all();
    worker_->thread.join();
  }
}

void MovieRecorder::observe(const World& world, double t_star) {
  FramePlan plan = maker_.plan(world, t_star);
  auto& w = *worker_;
  std::unique_lock lock(w.mutex);
  w.changed.wait(lock, [&] { return w.queue.size() < 4 || w.done; });
  if (w.error) std::rethrow_exception(w.error);
  w.queue.push_back(std::move(plan));
  lock.unlock();
  w.changed.notify_all();
  ++frames_;
}

void MovieRecorder::finish() {
  auto& w = *worker_;
  {
    std::lock_guard lock(w.mutex);
    w.closing = true;
  }
  w.changed.notify_all();
  if (w.thread.joinable()) w.thread.join();
  if (w.error) std::rethrow_exception(w.error);
  if (w.video) w.video->finish();
}

double MovieRecorder::draw_seconds() const { return worker_->draw_seconds; }

std::string snapshot_name(double t_star) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "snapshot_t%g.png", t_star);
  return buf;
}

SnapshotWriter::SnapshotWriter(const FrameOptions& frame, const SceneDef& scene, const SceneSetup& setup,
                               std::string dir, std::vector<double> times)
    : maker_(frame, scene, setup), dir_(std::move(dir)), times_(std::move(times)) {
  io::make_directories(dir_);
}

void SnapshotWriter::observe(const World& world, double t_star) {
  // The requested time this frame stands for: the nearest one.
  double requested = t_star, best = std::numeric_limits<double>::infinity();
  for (double t : times_)
    if (std::abs(t - t_star) < best) { best = std::abs(t - t_star); requested = t; }
  const std::string path = dir_ + "/" + snapshot_name(requested);
  write_png(path, maker_.make(world, t_star), maker_.options().transparent);
  written_.push_back(path);
}

}  // namespace runout::render

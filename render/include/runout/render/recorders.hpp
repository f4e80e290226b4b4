// Observers that turn a running simulation into pictures with no intermediate files: a movie
// (video and/or PNG sequence) at a fixed cadence, and snapshots at chosen t*.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "runout/render/frame.hpp"
#include "runout/render/batch_worker.hpp"
#include "runout/render/video.hpp"
#include "runout/observer.hpp"

namespace runout::render {

// The simulation thread only plans each frame (camera, colours: a copy of the disc state); a
// drawing thread draws it and hands it to the PNG writer and the video encoder's thread. They
// draw and encode a batch of plans at a time, on a core of their own: where the physics takes
// every core, it steps with one thread fewer until they are done (helper_cores). On two
// cores that costs the physics less than waiting for them did, as two threads step less than
// twice as fast as one, and the helpers' two threads fill the core they get.
class MovieRecorder : public Observer {
 public:
  // `video_path` empty: no video; `png_dir` empty: no PNG sequence. `first`: the World the
  // movie starts from (it sizes a frame of height 0).
  MovieRecorder(const FrameOptions& frame, const SceneDef& scene, const SceneSetup& setup, const World& first,
                const std::string& video_path, const VideoOptions& video, const std::string& png_dir);
  const FrameOptions& frame() const { return maker_.options(); }  // with the height resolved
  ~MovieRecorder() override;
  void observe(const World& world, const RunState&, double t_star) override;
  int helper_cores() override;
  void finish();  // draws what is queued and completes the video file; rethrows worker errors
  long frames() const { return frames_; }

 private:
  void draw(const FramePlan& plan);
  // Plans drawn and encoded at a time (at most the video's queue_frames, so drawing a batch
  // never waits for the encoder's queue).
  static constexpr std::size_t kBatch = 8;
  bool drawing_ = false;  // a batch is open to the helpers

  FrameMaker maker_;
  std::optional<VideoWriter> video_;
  std::string png_dir_;
  bool keep_alpha_ = false;
  long frames_ = 0, drawn_ = 0;
  std::unique_ptr<BatchWorker<FramePlan>> worker_;  // last: stops before the members it uses
};

// Writes DIR/snapshot_t<T>.png (or .pdf, .svg) for each requested T (the frame is the step
// nearest T; its stamp shows the actual t*).
class SnapshotWriter : public Observer {
 public:
  SnapshotWriter(const FrameOptions& frame, const SceneDef& scene, const SceneSetup& setup, const World& first,
                 std::string dir, std::vector<double> times, PictureFormat format = PictureFormat::png);
  void observe(const World& world, const RunState&, double t_star) override;
  std::vector<std::string> written() const { return written_; }

 private:
  FrameMaker maker_;
  std::string dir_;
  std::vector<double> times_;
  PictureFormat format_;
  std::vector<std::string> written_;
};

// "snapshot_t40.png", "snapshot_t2.5.pdf"
std::string snapshot_name(double t_star, PictureFormat format = PictureFormat::png);
// A frame written in `format`: a PNG (alpha kept if the frame is transparent), or a PDF or SVG.
void write_picture(const std::string& path, FrameMaker& maker, const World& world, double t_star,
                   PictureFormat format);

}  // namespace runout::render

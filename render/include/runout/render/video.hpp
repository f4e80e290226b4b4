// Video through FFmpeg's libraries: H.264 (libx264) in MP4, yuv420p (BT.601 matrix, limited
// range, tagged so every player shows it right); or a lossless H.264 (yuv444p, qp 0) for archiving. Frames are encoded
// on a worker thread, overlapped with the simulation; the file appears under its name only
// when complete (temp file + rename).
#pragma once

#include <memory>
#include <string>

#include "runout/render/image.hpp"

namespace runout::render {

struct VideoOptions {
  int fps = 30;
  int crf = 20;                  // x264 constant rate factor, 0..51 (lower = better)
  std::string preset = "ultrafast";
  bool lossless = false;         // yuv444p, qp 0: exact colours, not playable in browsers
  int queue_frames = 8;          // frames waiting for the encoder before write() blocks (while encoding)
};

class VideoWriter {
 public:
  // Opens `path` (format from its extension, .mp4 or .mkv) for width x height frames (even
  // numbers). Throws RenderError with the reason (no libx264, unwritable path, ...).
  VideoWriter(const std::string& path, int width, int height, const VideoOptions& options);
  ~VideoWriter();  // abandons an unfinished file (removes the temp file)
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;

  void write(const Image& frame);  // copied and queued; rethrows an encoder error from the worker
  // Encoding goes on beside the caller unless held (set_encoding(false)): frames then wait,
  // unbounded, until it is on again (a movie encodes a batch at a time, recorders.hpp).
  void set_encoding(bool on);
  bool encoded();  // every frame written so far is encoded (or the encoder stopped on an error)
  void finish();            // drains, writes the trailer, renames into place

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace runout::render

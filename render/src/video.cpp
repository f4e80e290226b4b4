#include "runout/render/video.hpp"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
}
#include <libyuv/convert.h>

#include <cstdio>
#include <mutex>
#include <vector>

#include "runout/render/gl_renderer.hpp"
#include "runout/render/batch_worker.hpp"

namespace runout::render {

namespace {

std::string av_error(int code) {
  char buf[AV_ERROR_MAX_STRING_SIZE] = {};
  av_strerror(code, buf, sizeof buf);
  return buf;
}

}  // namespace

struct VideoWriter::Impl {
  std::string path, temp_path;
  int width = 0, height = 0;
  VideoOptions options;
  AVFormatContext* format = nullptr;
  AVCodecContext* codec = nullptr;
  AVStream* stream = nullptr;
  SwsContext* sws = nullptr;
  AVFrame* frame = nullptr;
  AVPacket* packet = nullptr;
  long next_pts = 0;

  // Frames the encoder is done with, refilled by write(): a frame a write, with no allocation
  // and no fresh pages to fault in (3.7 MB at 1280x720; docs/performance_log.md, issue 12).
  std::mutex spare_mutex;
  std::vector<Image> spare;

  std::unique_ptr<BatchWorker<Image>> worker;  // converts and encodes off the caller's thread

  Image take_spare() {
    std::lock_guard lock(spare_mutex);
    if (spare.empty()) return {};
    Image img = std::move(spare.back());
    spare.pop_back();
    return img;
  }
  void give_back(Image&& img) {
    std::lock_guard lock(spare_mutex);
    spare.push_back(std::move(img));
  }

  ~Impl() {
    if (sws) sws_freeContext(sws);
    if (frame) av_frame_free(&frame);
    if (packet) av_packet_free(&packet);
    if (codec) avcodec_free_context(&codec);
    if (format) {
      if (format->pb) avio_closep(&format->pb);
      avformat_free_context(format);
    }
  }

  void drain_packets() {
    for (;;) {
      const int r = avcodec_receive_packet(codec, packet);
      if (r == AVERROR(EAGAIN) || r == AVERROR_EOF) return;
      if (r < 0) throw RenderError("video: encoding failed: " + av_error(r));
      // Each frame shows for one frame time; without it the MP4 muxer gives the last frame no
      // duration and players (and FFmpeg's decoder) drop it.
      if (packet->duration == 0) packet->duration = 1;
      av_packet_rescale_ts(packet, codec->time_base, stream->time_base);
      packet->stream_index = stream->index;
      const int w = av_interleaved_write_frame(format, packet);
      if (w < 0) throw RenderError("video: cannot write " + path + ": " + av_error(w));
    }
  }

  void encode(const Image& image) {
    if (av_frame_make_writable(frame) < 0) throw RenderError("video: out of memory");
    const std::uint8_t* src[1] = {image.rgba.data()};
    const int stride[1] = {image.width * 4};
    // libyuv's "ABGR" is R, G, B, A in memory, as Image has them; BT.601 limited range.
    if (!sws)
      libyuv::ABGRToI420(image.rgba.data(), stride[0], frame->data[0], frame->linesize[0], frame->data[1],
                         frame->linesize[1], frame->data[2], frame->linesize[2], width, height);
    else
      sws_scale(sws, src, stride, 0, height, frame->data, frame->linesize);
    frame->pts = next_pts++;
    const int r = avcodec_send_frame(codec, frame);
    if (r < 0) throw RenderError("video: encoding failed: " + av_error(r));
    drain_packets();
  }

  void close() {
    avcodec_send_frame(codec, nullptr);  // flush
    drain_packets();
    const int t = av_write_trailer(format);
    if (t < 0) throw RenderError("video: cannot finish " + path + ": " + av_error(t));
    avio_closep(&format->pb);
    if (std::rename(temp_path.c_str(), path.c_str()) != 0)
      throw RenderError("video: cannot move the finished file to " + path);
  }
};

VideoWriter::VideoWriter(const std::string& path, int width, int height, const VideoOptions& options)
    : impl_(std::make_unique<Impl>()) {
  auto& m = *impl_;
  if (width % 2 || height % 2)
    throw RenderError("video: frame size must be even for yuv420p (got " + std::to_string(width) + "x" +
                      std::to_string(height) + ")");
  if (options.fps < 1 || options.fps > 240) throw RenderError("video: fps must be in [1, 240]");
  if (options.crf < 0 || options.crf > 51) throw RenderError("video: crf must be in [0, 51]");
  m.path = path;
  m.temp_path = path + ".part";
  m.width = width;
  m.height = height;
  m.options = options;

  av_log_set_level(AV_LOG_ERROR);  // x264's statistics are not for the user's terminal
  const AVOutputFormat* guessed = av_guess_format(nullptr, path.c_str(), nullptr);
  if (!guessed) throw RenderError("video: cannot tell the container from " + path + " (use .mp4 or .mkv)");
  if (avformat_alloc_output_context2(&m.format, guessed, nullptr, m.temp_path.c_str()) < 0)
    throw RenderError("video: cannot create " + path);
  const AVCodec* encoder = avcodec_find_encoder_by_name("libx264");
  if (!encoder) throw RenderError("video: this FFmpeg has no libx264 encoder");
  m.stream = avformat_new_stream(m.format, nullptr);
  m.codec = avcodec_alloc_context3(encoder);
  if (!m.stream || !m.codec) throw RenderError("video: out of memory");
  m.codec->width = width;
  m.codec->height = height;
  m.codec->time_base = AVRational{1, options.fps};
  m.codec->framerate = AVRational{options.fps, 1};
  m.codec->pix_fmt = options.lossless ? AV_PIX_FMT_YUV444P : AV_PIX_FMT_YUV420P;
  // Tag the stream's matrix BT.601 and limited range, the conversion's below (libyuv's, and
  // libswscale's set to match); primaries and transfer are sRGB's, i.e. BT.709's.
  m.codec->colorspace = AVCOL_SPC_SMPTE170M;
  m.codec->color_primaries = AVCOL_PRI_BT709;
  m.codec->color_trc = AVCOL_TRC_BT709;
  m.codec->color_range = AVCOL_RANGE_MPEG;
  m.codec->thread_count = 1;  // one encoder thread beside the simulation
  if (m.format->oformat->flags & AVFMT_GLOBALHEADER) m.codec->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
  AVDictionary* opts = nullptr;
  av_dict_set(&opts, "preset", options.preset.c_str(), 0);
  if (options.lossless) av_dict_set(&opts, "qp", "0", 0);
  else av_dict_set(&opts, "crf", std::to_string(options.crf).c_str(), 0);
  const int opened = avcodec_open2(m.codec, encoder, &opts);
  av_dict_free(&opts);
  if (opened < 0) throw RenderError("video: libx264 refused the settings (preset \"" + options.preset + "\"): " + av_error(opened));
  avcodec_parameters_from_context(m.stream->codecpar, m.codec);
  m.stream->time_base = m.codec->time_base;
  if (const int r = avio_open(&m.format->pb, m.temp_path.c_str(), AVIO_FLAG_WRITE); r < 0)
    throw RenderError("video: cannot write " + path + ": " + av_error(r));
  if (const int r = avformat_write_header(m.format, nullptr); r < 0)
    throw RenderError("video: cannot write " + path + ": " + av_error(r));

  // yuv420p (every movie but a lossless one) by libyuv's vectorised RGBA to I420: 0.2 ms a
  // 1280x720 frame against libswscale's 2.4-3.4 ms on the encoder's thread
  // (docs/performance_log.md, issue 12, ninth session). yuv444p (lossless) by libswscale with
  // the same matrix.
  if (options.lossless) {
    m.sws = sws_getContext(width, height, AV_PIX_FMT_RGBA, width, height, m.codec->pix_fmt, SWS_BILINEAR, nullptr,
                           nullptr, nullptr);
    if (!m.sws) throw RenderError("video: no RGBA to YUV conversion");
    sws_setColorspaceDetails(m.sws, sws_getCoefficients(SWS_CS_ITU601), 1, sws_getCoefficients(SWS_CS_ITU601), 0,
                             0, 1 << 16, 1 << 16);
  }
  m.frame = av_frame_alloc();
  m.packet = av_packet_alloc();
  m.frame->format = m.codec->pix_fmt;
  m.frame->width = width;
  m.frame->height = height;
  if (!m.frame || !m.packet || av_frame_get_buffer(m.frame, 0) < 0) throw RenderError("video: out of memory");
  m.worker = std::make_unique<BatchWorker<Image>>(
      /*open=*/true,
      [&m](Image& image) {
        m.encode(image);
        m.give_back(std::move(image));
      },
      [&m] { m.close(); });
}

VideoWriter::~VideoWriter() {
  impl_->worker.reset();  // abandons an unfinished movie: no file under its name
  std::remove(impl_->temp_path.c_str());
}

void VideoWriter::write(const Image& frame) {
  if (frame.width != impl_->width || frame.height != impl_->height) throw RenderError("video: frame size changed");
  Image copy = impl_->take_spare();
  copy.width = frame.width;
  copy.height = frame.height;
  copy.rgba.assign(frame.rgba.begin(), frame.rgba.end());  // into the spare's own bytes
  impl_->worker->push(std::move(copy), static_cast<std::size_t>(impl_->options.queue_frames));
}

void VideoWriter::set_encoding(bool on) { impl_->worker->set_open(on); }
bool VideoWriter::encoded() { return impl_->worker->idle(); }

void VideoWriter::finish() { impl_->worker->finish(); }


}  // namespace runout::render

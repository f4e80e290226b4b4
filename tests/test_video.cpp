// The movie writer against FFmpeg's own reader: the file is opened and decoded by libavformat
// and libavcodec, and each decoded picture is turned back into RGB with the matrix and range
// the stream is tagged with, as a player does. Flat patches of the figure colours must come
// back as they went in: a conversion that disagrees with its tags shifts saturated colours by
// several levels, and a lost or repeated frame changes the count.
#include <gtest/gtest.h>

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libswscale/swscale.h>
}

#include <array>
#include <cstdlib>
#include <filesystem>
#include <vector>

#include "runout/render/image.hpp"
#include "runout/render/video.hpp"

namespace runout {
namespace {

using namespace render;

// Four flat quadrants in the colours a movie has most of: the background, the two species
// (Okabe–Ito blue and vermilion) and the walls' ink.
constexpr std::array<Rgba, 4> kPatches = {Rgba{255, 255, 255, 255}, Rgba{0, 114, 178, 255},
                                          Rgba{213, 94, 0, 255}, Rgba{51, 51, 51, 255}};

Image quadrants(int w, int h) {
  Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) img.set(x, y, kPatches[(2 * y >= h) * 2 + (2 * x >= w)]);
  return img;
}

int sws_matrix(AVColorSpace space) {
  switch (space) {
    case AVCOL_SPC_BT709: return SWS_CS_ITU709;
    case AVCOL_SPC_SMPTE170M:
    case AVCOL_SPC_BT470BG: return SWS_CS_ITU601;
    default: return -1;
  }
}

// Every picture of the file, in RGBA, converted by the stream's own tags.
struct Decoded {
  std::vector<Image> frames;
  AVColorSpace space = AVCOL_SPC_UNSPECIFIED;
  AVColorRange range = AVCOL_RANGE_UNSPECIFIED;
  double seconds = 0;  // the stream's duration, which players (and ffprobe) show frames within
};

Decoded decode(const std::string& path) {
  Decoded out;
  AVFormatContext* format = nullptr;
  EXPECT_EQ(avformat_open_input(&format, path.c_str(), nullptr, nullptr), 0) << path;
  if (!format) return out;
  EXPECT_GE(avformat_find_stream_info(format, nullptr), 0);
  const int index = av_find_best_stream(format, AVMEDIA_TYPE_VIDEO, -1, -1, nullptr, 0);
  EXPECT_GE(index, 0);
  const AVCodecParameters* par = format->streams[index]->codecpar;
  out.space = par->color_space;
  out.range = par->color_range;
  const AVStream* stream = format->streams[index];
  out.seconds = static_cast<double>(stream->duration) * av_q2d(stream->time_base);
  const AVCodec* decoder = avcodec_find_decoder(par->codec_id);
  AVCodecContext* codec = avcodec_alloc_context3(decoder);
  avcodec_parameters_to_context(codec, par);
  EXPECT_EQ(avcodec_open2(codec, decoder, nullptr), 0);
  AVPacket* packet = av_packet_alloc();
  AVFrame* frame = av_frame_alloc();
  SwsContext* sws = nullptr;
  auto receive = [&] {
    while (avcodec_receive_frame(codec, frame) == 0) {
      if (!sws) {
        sws = sws_getContext(frame->width, frame->height, static_cast<AVPixelFormat>(frame->format), frame->width,
                             frame->height, AV_PIX_FMT_RGBA, SWS_BILINEAR | SWS_ACCURATE_RND, nullptr, nullptr, nullptr);
        const int* coefficients = sws_getCoefficients(sws_matrix(out.space));
        sws_setColorspaceDetails(sws, coefficients, out.range == AVCOL_RANGE_JPEG, coefficients, 1, 0, 1 << 16,
                                 1 << 16);
      }
      Image img(frame->width, frame->height);
      std::uint8_t* dst[1] = {img.rgba.data()};
      const int stride[1] = {img.width * 4};
      sws_scale(sws, frame->data, frame->linesize, 0, frame->height, dst, stride);
      out.frames.push_back(std::move(img));
    }
  };
  while (av_read_frame(format, packet) >= 0) {
    if (packet->stream_index == index) {
      avcodec_send_packet(codec, packet);
      receive();
    }
    av_packet_unref(packet);
  }
  avcodec_send_packet(codec, nullptr);
  receive();
  sws_freeContext(sws);
  av_frame_free(&frame);
  av_packet_free(&packet);
  avcodec_free_context(&codec);
  avformat_close_input(&format);
  return out;
}

// The largest channel difference over the middle half of each quadrant (away from the edges,
// where 4:2:0 chroma and the encoder's blocks blur one patch into the next).
int worst_patch_error(const Image& img) {
  int worst = 0;
  for (int q = 0; q < 4; ++q) {
    const int x0 = (q % 2) * img.width / 2, y0 = (q / 2) * img.height / 2;
    for (int y = y0 + img.height / 8; y < y0 + 3 * img.height / 8; ++y)
      for (int x = x0 + img.width / 8; x < x0 + 3 * img.width / 8; ++x) {
        const Rgba got = img.at(x, y), want = kPatches[q];
        worst = std::max({worst, std::abs(got.r - want.r), std::abs(got.g - want.g), std::abs(got.b - want.b)});
      }
  }
  return worst;
}

class Movie : public ::testing::TestWithParam<bool> {};

TEST_P(Movie, FfmpegReadsBackEveryFrameInItsColours) {
  const bool lossless = GetParam();
  const auto path = std::filesystem::temp_directory_path() / (lossless ? "runout_video_lossless.mp4" : "runout_video.mp4");
  constexpr int kFrames = 12, kWidth = 320, kHeight = 240;
  VideoOptions options;
  options.lossless = lossless;
  {
    VideoWriter writer(path.string(), kWidth, kHeight, options);
    const Image img = quadrants(kWidth, kHeight);
    for (int k = 0; k < kFrames; ++k) writer.write(img);
    writer.finish();
  }
  const Decoded d = decode(path.string());
  EXPECT_EQ(d.range, AVCOL_RANGE_MPEG);
  ASSERT_GE(sws_matrix(d.space), 0) << "the stream's matrix is untagged or unknown: " << d.space;
  ASSERT_EQ(d.frames.size(), static_cast<std::size_t>(kFrames));
  // Every frame for one frame time: a last frame of no duration is dropped by players.
  EXPECT_NEAR(d.seconds, static_cast<double>(kFrames) / options.fps, 1e-6);
  for (const Image& img : d.frames) {
    ASSERT_EQ(img.width, kWidth);
    ASSERT_EQ(img.height, kHeight);
    // Limited-range 8-bit YUV rounds each colour to within ~2 levels; x264 at crf 20 on flat
    // patches adds at most one or two more. Tagged BT.709 instead, vermilion comes back 9 levels off.
    EXPECT_LE(worst_patch_error(img), lossless ? 2 : 4);
  }
  std::filesystem::remove(path);
}

INSTANTIATE_TEST_SUITE_P(BothKinds, Movie, ::testing::Values(false, true),
                         [](const auto& info) { return info.param ? "lossless" : "playable"; });

}  // namespace
}  // namespace runout

// The pictures live in a loadable module, runout_pictures.so, built beside the runout binary
// from picture_module.cpp and the renderer. The binary loads it on the first picture request
// (picture_loader.cpp), so a run that draws nothing never maps OSMesa, LLVM, FFmpeg, libpng
// or FreeType (docs/performance.md, "compute only what a scene needs").
#pragma once

#include <cstddef>

#include "pictures.hpp"

namespace runout::app {

inline constexpr int kPictureApiVersion = 1;

// What the module hands the binary. The layout checks refuse a module from another build.
struct PictureApi {
  int version = kPictureApiVersion;
  const char* build_stamp = nullptr;
  std::size_t world_size = 0, run_state_size = 0, picture_options_size = 0;
  decltype(&render_command) render = nullptr;
  decltype(&compare_command) compare = nullptr;
  decltype(&open_pictures) open = nullptr;
  decltype(&bench_frames) bench = nullptr;
};

inline PictureApi expected_picture_api_layout(const char* build_stamp) {
  PictureApi api;
  api.build_stamp = build_stamp;
  api.world_size = sizeof(World);
  api.run_state_size = sizeof(RunState);
  api.picture_options_size = sizeof(PictureOptions);
  return api;
}

}  // namespace runout::app

// The module's one exported symbol.
extern "C" __attribute__((visibility("default"))) const runout::app::PictureApi* runout_picture_api();
inline constexpr const char* kPictureApiSymbol = "runout_picture_api";

// The binary's side of the picture functions: each loads runout_pictures.so on first use and
// forwards to it. Nothing here touches a rendering library, so `runout run` without picture
// options maps none (docs/performance.md).
#include <dlfcn.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "picture_module.hpp"

namespace runout::app {

namespace {

// Where the module may be: $RUNOUT_PICTURES_MODULE, beside the binary (the build tree), then
// ../lib/runout/ (an installed tree).
std::vector<std::string> module_candidates() {
  std::vector<std::string> out;
  if (const char* env = std::getenv("RUNOUT_PICTURES_MODULE"); env && *env) return {env};
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    out.push_back((exe.parent_path() / "runout_pictures.so").string());
    out.push_back((exe.parent_path().parent_path() / "lib" / "runout" / "runout_pictures.so").string());
  }
  return out;
}

const PictureApi& load_module() {
  const PictureApi expected = expected_picture_api_layout(RUNOUT_BUILD_STAMP);
  std::string tried;
  for (const auto& path : module_candidates()) {
    if (!std::filesystem::exists(path)) {
      tried += "\n  " + path + " (absent)";
      continue;
    }
    void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) throw std::runtime_error("cannot load the picture module " + path + ": " + dlerror());
    auto entry = reinterpret_cast<decltype(&runout_picture_api)>(dlsym(handle, kPictureApiSymbol));
    const PictureApi* api = entry ? entry() : nullptr;
    if (!api || api->version != expected.version || std::strcmp(api->build_stamp, expected.build_stamp) != 0 ||
        api->world_size != expected.world_size || api->run_state_size != expected.run_state_size ||
        api->picture_options_size != expected.picture_options_size) {
      dlclose(handle);
      throw std::runtime_error("the picture module " + path +
                               " is from another build of runout; rebuild (cmake --build) or install both together");
    }
    // Kept loaded for the life of the process: observers and frames it made are still in use.
    return *api;
  }
  throw std::runtime_error(
      "this runout cannot draw: its picture module runout_pictures.so was not found" + tried +
      "\nIt is built with the renderer (install libosmesa6-dev, libpng-dev, libavcodec-dev, libavformat-dev, "
      "libswscale-dev, libfreetype-dev, libcairo2-dev, libisal-dev, libyuv-dev and rebuild), or point RUNOUT_PICTURES_MODULE at it");
}

// Loaded once per process, on the first picture request (a function-local static: the
// dynamic linker's own state is per process too).
const PictureApi& pictures() {
  static const PictureApi& api = load_module();
  return api;
}

}  // namespace

int render_command(const RenderOptions& o) { return pictures().render(o); }
int compare_command(const CompareOptions& o) { return pictures().compare(o); }
std::unique_ptr<PictureSession> open_pictures(const PictureOptions& o, const World& world, const SceneDef& scene,
                                              const SceneSetup& setup, const std::string& out_dir) {
  return pictures().open(o, world, scene, setup, out_dir);
}
int bench_frames(World& world, const SceneDef& scene, const SceneSetup& setup, const PictureOptions& o,
                 long long frames, long long steps_between) {
  return pictures().bench(world, scene, setup, o, frames, steps_between);
}

}  // namespace runout::app

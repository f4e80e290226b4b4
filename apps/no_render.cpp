// Stand-ins used when runout is built without the renderer: every picture option is refused
// with a clear message instead of being ignored.
#include <CLI/CLI.hpp>
#include <stdexcept>

#include "render_cli.hpp"

namespace runout::app {

bool have_renderer() { return false; }

namespace {
[[noreturn]] void refuse() {
  throw std::runtime_error("this runout was built without the renderer (install libosmesa6-dev, libpng-dev, "
                           "libavcodec-dev, libavformat-dev, libswscale-dev, libfreetype-dev and rebuild)");
}
}  // namespace

int render_command(const RenderOptions&) { refuse(); }
int bench_frames(World&, const SceneDef&, const SceneSetup&, const PictureOptions&, long long, long long) { refuse(); }
int compare_command(const CompareOptions&) { refuse(); }
void plot_study(const std::vector<StudyPoint>&, const std::string&, const std::string&) { refuse(); }
std::unique_ptr<PictureSession> attach_pictures(const PictureOptions&, AvalancheRun&, const SceneDef&,
                                                const SceneSetup&, const std::string&) {
  refuse();
}

}  // namespace runout::app

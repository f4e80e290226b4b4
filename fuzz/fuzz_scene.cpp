// libFuzzer target: the scene reader with --set overrides, then everything `runout run` checks
// before it steps (derivation, runnability, the explicit world). Input: TOML text, then any
// number of NUL-separated `key=value` overrides. A ConfigError is the expected answer to bad
// input; any other exception, a crash, a hang or a resolved scene that does not read back to
// itself is a finding.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

#include "runout/errors.hpp"
#include "runout/io/scene_file.hpp"
#include "runout/setup.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view in(reinterpret_cast<const char*>(data), size);
  const std::size_t cut = in.find('\0');
  const std::string text(in.substr(0, cut));
  std::vector<runout::io::Override> overrides;
  try {
    for (std::size_t at = cut; at != std::string_view::npos && at < in.size();) {
      const std::size_t next = in.find('\0', at + 1);
      overrides.push_back(runout::io::parse_override(std::string(in.substr(at + 1, next - at - 1))));
      at = next;
    }
    const runout::SceneDef scene = runout::io::read_scene(text, "fuzz.toml", overrides);
    const runout::SceneSetup setup = runout::derive_setup(scene, "fuzz.toml");
    runout::check_runnable(scene, setup, "fuzz.toml");
    // The resolved scene is what a resumed or repeated run reads: it must read back to itself.
    const std::string resolved = runout::io::write_scene(scene);
    const runout::SceneDef again = runout::io::read_scene(resolved, "scene.resolved.toml");
    if (runout::io::write_scene(again) != resolved ||
        runout::io::physics_key(again) != runout::io::physics_key(scene))
      std::abort();
    if (!scene.avalanche) runout::build_explicit_world(scene, setup, 1);
  } catch (const runout::ConfigError&) {
  }
  return 0;
}

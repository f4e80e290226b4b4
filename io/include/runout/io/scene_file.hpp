// Scene files in TOML (toml++), read strictly into SceneDef: an unknown key, a wrong type or an
// out-of-range value is a ConfigError naming the file, the key and what is allowed.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "runout/scene.hpp"

namespace runout::io {

// One `--set key=value` override: a dotted key path and a TOML value ("0.12", "\"hertz\"",
// or a bare word, read as a string).
struct Override {
  std::string key;
  std::string value;
};
Override parse_override(const std::string& text);  // "a.b=c"; throws ConfigError

// Reads a scene from TOML text; `source` names it in errors (a path or "<embedded quick>").
SceneDef read_scene(const std::string& text, const std::string& source,
                    const std::vector<Override>& overrides = {});
SceneDef read_scene_file(const std::string& path, const std::vector<Override>& overrides = {});

// Every value of a scene, defaults included, as TOML that read_scene reads back to the same
// scene (scene.resolved.toml).
std::string write_scene(const SceneDef& scene);

// The TOML of the parts of a scene that decide the settled pile (material, contact,
// integration, species, avalanche, preparation): the key of the pile cache.
std::string pile_key_text(const SceneDef& scene);

// Key of a run's physics: the scene without its name, stopping and output settings, so a run
// can be resumed with a later max_time but never under other physics (checkpoints).
std::uint64_t physics_key(const SceneDef& scene);

// The quick pile embedded in the binary (examples/quick.toml).
const std::string& embedded_quick_scene();
// The bench scene: the thesis pile D/d = 4, %A_p = 40 (examples/thesis_4_40.toml).
const std::string& embedded_bench_scene();

// One key of a scene's flat tables with what it allows, its default and its meaning, from the
// one list the reader and the writer use (`runout keys`). [species.NAME], [[walls]] and
// [[particles]] have structure: the README's "Scene files" describes them.
struct SceneKey {
  std::string key, allowed, default_value, meaning;
};
std::vector<SceneKey> scene_keys();

const char* to_string(IntegratorKind k);
const char* to_string(SizeDistribution d);

}  // namespace runout::io

// `runout keys`: every key of a scene file's flat tables with what it allows, its default and
// its meaning, from the same list the scene reader and writer use (io/src/scene_keys.hpp).
#include <algorithm>
#include <cstdio>

#include <nlohmann/json.hpp>

#include "run_command.hpp"
#include "runout/io/scene_file.hpp"

namespace runout::app {

int keys_command(const KeysOptions& o) {
  const std::vector<io::SceneKey> keys = io::scene_keys();
  if (o.json) {
    nlohmann::json j = nlohmann::json::array();
    for (const auto& k : keys)
      j.push_back({{"key", k.key}, {"allowed", k.allowed}, {"default", k.default_value}, {"meaning", k.meaning}});
    std::printf("%s\n", j.dump(2).c_str());
    return 0;
  }
  // As TOML with every default, one table after another, so it can be copied into a scene;
  // the comments line up within a table.
  auto table_of = [](const io::SceneKey& k) { return k.key.substr(0, k.key.find('.')); };
  auto line_of = [](const io::SceneKey& k) { return k.key.substr(k.key.find('.') + 1) + " = " + k.default_value; };
  for (std::size_t first = 0, last; first < keys.size(); first = last) {
    std::size_t width = 0;
    for (last = first; last < keys.size() && table_of(keys[last]) == table_of(keys[first]); ++last)
      width = std::max(width, line_of(keys[last]).size());
    std::printf("%s[%s]\n", first ? "\n" : "", table_of(keys[first]).c_str());
    for (std::size_t k = first; k < last; ++k)
      std::printf("%-*s  # %s: %s\n", int(width), line_of(keys[k]).c_str(), keys[k].allowed.c_str(),
                  keys[k].meaning.c_str());
  }
  std::printf("\n# [species.NAME], [[walls]] and [[particles]]: see the README's \"Scene files\".\n");
  return 0;
}

}  // namespace runout::app

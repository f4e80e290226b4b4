// Writing a scene: every value, defaults included, as TOML that reads back to the same scene
// (scene.resolved.toml), the keys of a run's physics and of its settled pile, and the list
// of keys `runout keys` prints; the flat tables from their key lists (scene_keys.hpp).
#include <toml++/toml.h>

#include <sstream>
#include <utility>

#include "runout/io/files.hpp"
#include "runout/io/scene_file.hpp"
#include "scene_keys.hpp"

namespace runout::io {

namespace {

// Writes a section's keys into a TOML table (scene.resolved.toml, the physics and pile keys).
struct KeyWriter {
  toml::table& t;
  void number(const char* k, double v, Range, const char*) { t.insert(k, v); }
  template <class Int>
  void integer(const char* k, Int v, double, double, const char*) { t.insert(k, static_cast<std::int64_t>(v)); }
  template <class T>
  void choice(const char* k, const T& v, const Options<T>& options, const char*) {
    for (const auto& [name, value] : options)
      if (value == v) t.insert(k, name);
  }
  template <class Flags, std::size_t N>
  void flags(const char* k, const Flags& v, const std::pair<const char*, bool Flags::*> (&names)[N], const char*) {
    toml::array list;
    for (const auto& [name, flag] : names)
      if (v.*flag) list.push_back(name);
    t.insert(k, list);
  }
};

template <class List>
toml::table write_section(List&& list) {
  toml::table t;
  KeyWriter writer{t};
  list(writer);
  return t;
}

// Lists a section's keys with what they allow and their defaults (`runout keys`).
struct KeyLister {
  std::string table;
  std::vector<SceneKey>& out;
  void add(const char* k, std::string allowed, std::string value, const char* meaning) {
    out.push_back({table + "." + k, std::move(allowed), std::move(value), meaning});
  }
  void number(const char* k, double v, Range range, const char* meaning) {
    add(k, "number in " + range.text(), format_number(v), meaning);
  }
  template <class Int>
  void integer(const char* k, Int v, double lo, double hi, const char* meaning) {
    add(k, "integer in " + closed(lo, hi).text(), std::to_string(v), meaning);
  }
  template <class T>
  void choice(const char* k, const T& v, const Options<T>& options, const char* meaning) {
    std::string allowed, value;
    for (const auto& [name, option] : options) {
      allowed += (allowed.empty() ? "\"" : " | \"") + name + "\"";
      if (option == v) value = "\"" + name + "\"";
    }
    add(k, allowed, value, meaning);
  }
  template <class Flags, std::size_t N>
  void flags(const char* k, const Flags& v, const std::pair<const char*, bool Flags::*> (&names)[N], const char* meaning) {
    std::string allowed, value;
    for (const auto& [name, flag] : names) {
      allowed += (allowed.empty() ? "list of \"" : ", \"") + std::string(name) + "\"";
      if (v.*flag) value += (value.empty() ? "\"" : ", \"") + std::string(name) + "\"";
    }
    add(k, allowed, "[" + value + "]", meaning);
  }
};

toml::table physics_tables(const SceneDef& s, bool include_rest) {
  toml::table root;
  root.insert("name", s.name);
  root.insert("material", write_section([&](auto& v) { material_keys(s.material, v); }));
  root.insert("contact", write_section([&](auto& v) { contact_keys(s.contact, v); }));
  root.insert("integration", write_section([&](auto& v) { integration_keys(s.integration, v); }));
  toml::table species;
  for (const auto& sp : s.species) {
    if (sp.distribution == SizeDistribution::spread) {
      species.insert(sp.name, toml::table{{"diameter", sp.diameter},
                                          {"spread", sp.spread},
                                          {"area_share", sp.area_share}});
      continue;
    }
    // A class is written as a one-class distribution: it reads back as itself.
    toml::table t{{"distribution", to_string(sp.distribution)},
                  {"min", sp.min_diameter},
                  {"max", sp.max_diameter},
                  {"area_share", sp.area_share}};
    if (sp.distribution == SizeDistribution::lognormal) {
      t.insert("median", sp.median);
      t.insert("sigma", sp.sigma);
    }
    species.insert(sp.name, t);
  }
  root.insert("species", species);
  if (s.avalanche) {
    root.insert("avalanche", write_section([&](auto& v) { avalanche_keys(*s.avalanche, v); }));
    root.insert("preparation", write_section([&](auto& v) { preparation_keys(s.preparation, v); }));
  }
  if (include_rest) {
    root.insert("rest", write_section([&](auto& v) { rest_keys(s.rest, v); }));
    root.insert("output", write_section([&](auto& v) { output_keys(s.output, v); }));
  }
  return root;
}

// The whole scene as a table: what scene.resolved.toml says and the physics key is made of.
toml::table scene_table(const SceneDef& s) {
  toml::table root = physics_tables(s, true);
  if (!s.walls.empty()) {
    toml::array walls;
    for (const auto& w : s.walls) {
      toml::array pts;
      for (const auto& [x, y] : w.points) pts.push_back(toml::array{x, y});
      const char* inside = "both";
      for (const auto& [name, value] : kWallSides)
        if (value == w.inside) inside = name.c_str();
      walls.push_back(toml::table{{"name", w.name}, {"points", pts}, {"bed", w.bed}, {"inside", inside}});
    }
    root.insert("walls", walls);
  }
  if (!s.particles.empty()) {
    toml::array parts;
    for (const auto& p : s.particles)
      parts.push_back(toml::table{{"species", s.species[p.species].name}, {"x", p.x}, {"y", p.y},
                                  {"vx", p.vx}, {"vy", p.vy}, {"omega", p.omega},
                                  {"diameter", p.diameter}});
    root.insert("particles", parts);
  }
  return root;
}

std::string format_scene(const toml::table& root) {
  std::ostringstream out;
  out << "# Every value this run used, defaults included (runout scene.resolved.toml)\n";
  out << toml::toml_formatter(root, toml::toml_formatter::default_flags &
                                        ~toml::format_flags::allow_literal_strings)
      << "\n";
  return out.str();
}

}  // namespace

const char* to_string(IntegratorKind k) {
  for (const auto& [name, value] : kIntegrators)
    if (value == k) return name.c_str();
  return "?";
}
const char* to_string(SizeDistribution d) {
  for (const auto& [name, value] : kDistributions)
    if (value == d) return name.c_str();
  return "spread";
}

std::vector<SceneKey> scene_keys() {
  const SceneDef s;
  const AvalancheDef avalanche;
  std::vector<SceneKey> keys;
  auto list = [&](const char* table, auto&& section) {
    KeyLister lister{table, keys};
    section(lister);
  };
  list("material", [&](auto& v) { material_keys(s.material, v); });
  list("contact", [&](auto& v) { contact_keys(s.contact, v); });
  list("integration", [&](auto& v) { integration_keys(s.integration, v); });
  list("avalanche", [&](auto& v) { avalanche_keys(avalanche, v); });
  list("preparation", [&](auto& v) { preparation_keys(s.preparation, v); });
  list("rest", [&](auto& v) { rest_keys(s.rest, v); });
  list("output", [&](auto& v) { output_keys(s.output, v); });
  return keys;
}

std::string write_scene(const SceneDef& s) { return format_scene(scene_table(s)); }

std::uint64_t physics_key(const SceneDef& scene) {
  SceneDef s = scene;
  s.rest = RestDef{};
  s.output = OutputDef{};
  s.name.clear();
  toml::table root = scene_table(s);
  // The key is the text of the scene with its output settings at their defaults, so an output
  // key added later would change every key and orphan the checkpoints written before it (a run
  // could no longer be resumed or drawn). Keys added to [output] since are left out of it.
  for (const char* added : {"vtk_every"}) root["output"].as_table()->erase(added);
  return fnv1a64(format_scene(root));
}

std::string pile_key_text(const SceneDef& s) {
  toml::table root = physics_tables(s, false);
  root.erase("name");
  // The skin changes the cost, never the trajectory (tests/test_neighbors.cpp), so piles
  // settled with any skin are shared.
  root["integration"].as_table()->erase("skin");
  std::ostringstream out;
  out << root;
  return out.str();
}

const std::string& embedded_quick_scene() {
  static const std::string text =
#include "quick_scene.inc"
      ;
  return text;
}

const std::string& embedded_bench_scene() {
  static const std::string text =
#include "thesis_4_40_scene.inc"
      ;
  return text;
}

}  // namespace runout::io

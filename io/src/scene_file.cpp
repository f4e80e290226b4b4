// Reading a scene file: TOML (toml++) into SceneDef, --set overrides applied first, every key
// checked against its list (scene_keys.hpp) or, for the tables with structure, here.
#include "runout/io/scene_file.hpp"

#include <toml++/toml.h>

#include <cmath>
#include <sstream>
#include <utility>

#include "runout/contact/registry.hpp"
#include "runout/errors.hpp"
#include "runout/io/files.hpp"
#include "runout/size_distribution.hpp"
#include "table_reader.hpp"

namespace runout::io {

namespace {

// Applies one --set to the parsed document.
void apply_override(toml::table& root, const Override& o, const std::string& source) {
  toml::table* t = &root;
  std::vector<std::string> parts;
  std::stringstream ss(o.key);
  for (std::string part; std::getline(ss, part, '.');) parts.push_back(part);
  for (size_t i = 0; i + 1 < parts.size(); ++i) {
    toml::node* n = t->get(parts[i]);
    if (!n) {
      t->insert(parts[i], toml::table{});
      n = t->get(parts[i]);
    }
    if (!n->is_table())
      throw ConfigError(source, o.key, "--set can only set keys inside tables, and " + parts[i] + " is not a table");
    t = n->as_table();
  }
  toml::table parsed;
  try {
    parsed = toml::parse("v = " + o.value);
  } catch (const toml::parse_error&) {
    parsed = toml::table{};
    parsed.insert("v", o.value);  // a bare word: the string itself
  }
  t->insert_or_assign(parts.back(), *parsed.get("v"));
}

std::pair<double, double> read_point(const toml::node& n, const std::string& source,
                                     const std::string& key) {
  const toml::array* a = n.as_array();
  if (!a || a->size() != 2 || !(*a)[0].is_number() || !(*a)[1].is_number())
    throw ConfigError(source, key, "expected a point [x, y] of two numbers");
  auto num = [](const toml::node& v) {
    return v.is_integer() ? double(v.as_integer()->get()) : v.as_floating_point()->get();
  };
  const double x = num((*a)[0]), y = num((*a)[1]);
  if (!std::isfinite(x) || !std::isfinite(y)) throw ConfigError(source, key, "coordinates must be finite");
  return {x, y};
}

// A continuous size distribution by area in [species.NAME]: distribution, min, max (m), for
// lognormal median (m) and sigma (of ln d), classes (species it is split into) and area_share.
void read_distribution(TableReader& r, const std::string& name, std::vector<SpeciesDef>& out) {
  r.allow({"distribution", "min", "max", "median", "sigma", "classes", "area_share"}, "");
  SpeciesDef f;
  f.name = name;
  r.choice("distribution", f.distribution, kDistributions);
  for (const char* k : {"min", "max"})
    if (!r.has(k)) r.fail(k, "is required with a distribution (metres, > 0)");
  r.number("min", f.min_diameter, positive(1e6));
  r.number("max", f.max_diameter, positive(1e6));
  if (!(f.max_diameter > f.min_diameter))
    r.fail("max", "must be larger than min (" + format_number(f.max_diameter) + " <= " + format_number(f.min_diameter) + ")");
  if (f.max_diameter > 100 * f.min_diameter)
    r.fail("max", "is more than 100 times min: the smallest discs would set a time step too small for the largest");
  if (f.distribution == SizeDistribution::lognormal) {
    for (const char* k : {"median", "sigma"})
      if (!r.has(k)) r.fail(k, "is required for a lognormal distribution (median: metres; sigma: of ln d)");
    r.number("median", f.median, positive(1e6));
    r.number("sigma", f.sigma, {0, 3, true, false});
    const double za = std::log(f.min_diameter / f.median) / f.sigma, zb = std::log(f.max_diameter / f.median) / f.sigma;
    if (0.5 * (std::erfc(-zb / std::sqrt(2.0)) - std::erfc(-za / std::sqrt(2.0))) < 1e-6)
      r.fail("median", "and sigma put less than a millionth of the area between min and max");
  } else {
    for (const char* k : {"median", "sigma"})
      if (r.has(k)) r.fail(k, "belongs to a lognormal distribution (this one is uniform)");
  }
  int classes = 1;
  r.integer("classes", classes, 1, 16);
  r.number("area_share", f.area_share, closed(0, 1));
  r.finish();
  for (SpeciesDef& c : split_into_classes(f, classes)) out.push_back(std::move(c));
}

SceneDef read_document(const toml::table& root, const std::string& source) {
  SceneDef s;
  TableReader top(root, "", source);
  top.allow({"name", "material", "contact", "integration", "species", "avalanche", "preparation",
             "rest", "output", "walls", "particles"}, "");
  top.string("name", s.name);

  read_section(top, "material", source, [&](auto& v) { material_keys(s.material, v); });
  read_section(top, "contact", source, [&](auto& v) { contact_keys(s.contact, v); });
  // A law may be defined only with one normal law (its registry row says which).
  TangentialLaws::with(s.contact.tangential_model, [&](auto law) {
    using Law = decltype(law);
    if constexpr (requires { Law::kNormalLaw; })
      if (s.contact.normal_model != Law::kNormalLaw)
        throw ConfigError(source, "contact.tangential_model",
                          "\"" + s.contact.tangential_model + "\" needs contact.normal_model = \"" +
                              Law::kNormalLaw + "\" (it is \"" + s.contact.normal_model + "\")");
  });
  read_section(top, "integration", source, [&](auto& v) { integration_keys(s.integration, v); });
  if (auto t = top.subtable("species")) {
    for (auto&& [k, v] : *t) {
      const std::string name(k.str());
      if (!v.is_table()) throw ConfigError(source, "species." + name, "expected a table [species." + name + "]");
      TableReader r(*v.as_table(), "species." + name, source);
      if (r.has("distribution")) {
        read_distribution(r, name, s.species);
        continue;
      }
      r.allow({"diameter", "spread", "area_share"}, " (or distribution = \"uniform\" | \"lognormal\" with min, max, ...)");
      SpeciesDef sp;
      sp.name = name;
      if (!r.has("diameter")) r.fail("diameter", "is required (metres, > 0)");
      r.number("diameter", sp.diameter, positive(1e6));
      r.number("spread", sp.spread, {0, 1, false, true});
      r.number("area_share", sp.area_share, closed(0, 1));
      r.finish();
      s.species.push_back(sp);
    }
  }
  if (s.species.empty())
    throw ConfigError(source, "species", "at least one [species.NAME] table with a diameter is required");
  if (s.species.size() > 64) throw ConfigError(source, "species", "at most 64 species");
  for (std::size_t a = 0; a < s.species.size(); ++a)
    for (std::size_t b = a + 1; b < s.species.size(); ++b)
      if (s.species[a].name == s.species[b].name)
        throw ConfigError(source, "species." + s.species[b].name,
                          "is declared twice (a distribution's classes are named NAME_1 .. NAME_N)");

  if (top.has("avalanche")) {
    AvalancheDef a;
    read_section(top, "avalanche", source, [&](auto& v) { avalanche_keys(a, v); });
    s.avalanche = a;
    double share = 0;
    for (const auto& sp : s.species) share += sp.area_share;
    if (std::abs(share - 1.0) > 1e-9)
      throw ConfigError(source, "species.*.area_share",
                        "the area shares of an avalanche's species must add up to 1 (they add up to " +
                            format_number(share) + ")");
  }
  read_section(top, "preparation", source, [&](auto& v) { preparation_keys(s.preparation, v); });
  read_section(top, "rest", source, [&](auto& v) { rest_keys(s.rest, v); });
  read_section(top, "output", source, [&](auto& v) { output_keys(s.output, v); });

  auto species_index = [&](const std::string& name, const std::string& key) {
    for (size_t k = 0; k < s.species.size(); ++k)
      if (s.species[k].name == name) return static_cast<int>(k);
    std::string allowed;
    for (const auto& sp : s.species) allowed += (allowed.empty() ? "" : ", ") + ("\"" + sp.name + "\"");
    throw ConfigError(source, key, "unknown species \"" + name + "\" (declared: " + allowed + ")");
  };

  if (auto a = top.array("walls")) {
    for (size_t w = 0; w < a->size(); ++w) {
      const std::string key = "walls[" + std::to_string(w) + "]";
      if (!(*a)[w].is_table()) throw ConfigError(source, key, "expected a table [[walls]]");
      TableReader r(*(*a)[w].as_table(), key, source);
      r.allow({"name", "points", "bed", "inside"}, "");
      WallDef wall;
      wall.name = "wall" + std::to_string(w);
      r.string("name", wall.name);
      r.boolean("bed", wall.bed);
      const toml::array* pts = r.array("points");
      if (!pts || pts->size() < 2) r.fail("points", "a wall needs at least two points [[x, y], [x, y], ...]");
      for (size_t k = 0; k < pts->size(); ++k)
        wall.points.push_back(read_point((*pts)[k], source, r.key("points[" + std::to_string(k) + "]")));
      for (size_t k = 0; k + 1 < wall.points.size(); ++k)
        if (wall.points[k] == wall.points[k + 1])
          r.fail("points[" + std::to_string(k + 1) + "]", "repeats the point before it (a zero-length segment)");
      // Which side the discs are on is the scene's to say (walls.hpp): a one-sided face can
      // never be passed, a two-sided plate can be once a squeezed disc's centre crosses it.
      if (!r.has("inside"))
        r.fail("inside", "is required: \"left\" or \"right\" of the direction from points[0] to "
                         "points[1] (the side the discs are on; a one-sided wall no disc passes "
                         "through), or \"both\" (a thin two-sided plate)");
      r.choice("inside", wall.inside, kWallSides);
      r.finish();
      s.walls.push_back(wall);
    }
  }
  if (auto a = top.array("particles")) {
    if (s.avalanche) throw ConfigError(source, "particles", "a scene has either [avalanche] or explicit [[particles]], not both");
    for (size_t k = 0; k < a->size(); ++k) {
      const std::string key = "particles[" + std::to_string(k) + "]";
      if (!(*a)[k].is_table()) throw ConfigError(source, key, "expected a table [[particles]]");
      TableReader r(*(*a)[k].as_table(), key, source);
      r.allow({"species", "x", "y", "vx", "vy", "omega", "diameter"}, "");
      ParticleDef p;
      std::string sp_name = s.species.size() == 1 ? s.species[0].name : "";
      r.string("species", sp_name);
      if (sp_name.empty()) r.fail("species", "is required when the scene has several species");
      p.species = species_index(sp_name, r.key("species"));
      p.diameter = s.species[p.species].diameter;
      r.number("x", p.x, closed(-1e9, 1e9));
      r.number("y", p.y, closed(-1e9, 1e9));
      r.number("vx", p.vx, closed(-1e6, 1e6));
      r.number("vy", p.vy, closed(-1e6, 1e6));
      r.number("omega", p.omega, closed(-1e9, 1e9));
      r.number("diameter", p.diameter, positive(1e6));
      r.finish();
      s.particles.push_back(p);
    }
  }
  top.finish();
  if (!s.avalanche && s.particles.empty() && s.walls.empty())
    throw ConfigError(source, "avalanche", "the scene has no [avalanche], no [[particles]] and no [[walls]]: nothing to simulate");
  return s;
}

}  // namespace

Override parse_override(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == text.size())
    throw ConfigError("--set", text, "expected key=value, e.g. --set contact.normal_model=hertz");
  return {text.substr(0, eq), text.substr(eq + 1)};
}

SceneDef read_scene(const std::string& text, const std::string& source,
                    const std::vector<Override>& overrides) {
  toml::table root;
  try {
    root = toml::parse(text, source);
  } catch (const toml::parse_error& e) {
    std::ostringstream where;
    where << "line " << e.source().begin.line << ", column " << e.source().begin.column;
    throw ConfigError(source, where.str(), std::string(e.description()));
  }
  for (const auto& o : overrides) apply_override(root, o, "--set " + o.key + "=" + o.value);
  return read_document(root, source);
}

SceneDef read_scene_file(const std::string& path, const std::vector<Override>& overrides) {
  std::string text;
  try {
    // 64 MiB: far above any scene (a thesis scene is under 1 kB; explicit discs take ~60 bytes each).
    text = read_regular_file(path, 64u << 20);
  } catch (const IoError& e) {
    throw ConfigError(path, "(file)", e.what());
  }
  return read_scene(text, path, overrides);
}

}  // namespace runout::io

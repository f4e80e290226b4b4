#include "runout/io/scene_file.hpp"

#include <toml++/toml.h>

#include <cstdio>
#include <cstdlib>
#include <cmath>
#include <limits>
#include <set>
#include <utility>
#include <sstream>

#include "runout/contact/registry.hpp"
#include "runout/errors.hpp"
#include "runout/io/files.hpp"
#include "runout/size_distribution.hpp"

namespace runout::io {

namespace {

// The names of output.series, read and written from this one list.
constexpr std::pair<const char*, bool SeriesSelection::*> kSeriesNames[] = {
    {"energy", &SeriesSelection::energy}, {"segregation", &SeriesSelection::segregation},
    {"basal_spin", &SeriesSelection::basal_spin}, {"front", &SeriesSelection::front},
    {"overlap", &SeriesSelection::overlap}};

constexpr double kInf = std::numeric_limits<double>::infinity();

// The shortest text that reads back as the same double (the -0.1 a user typed is "-0.1", not
// -0.10000000000000001, and no two different values print alike); whole numbers in full.
std::string format_number(double v) {
  char buf[48];
  if (std::isfinite(v) && v == std::floor(v) && std::abs(v) < 1e15) {
    std::snprintf(buf, sizeof buf, "%.0f", v);
    return buf;
  }
  for (int digits = 1; digits <= 17; ++digits) {
    std::snprintf(buf, sizeof buf, "%.*g", digits, v);
    if (std::strtod(buf, nullptr) == v) break;
  }
  return buf;
}

// A numeric interval with open or closed ends, printed the way a user reads it: "(0, 1]".
struct Range {
  double lo = -kInf, hi = kInf;
  bool lo_open = false, hi_open = false;
  bool contains(double v) const {
    return (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
  }
  std::string text() const {
    auto end = [](double v) { return std::isinf(v) ? std::string(v < 0 ? "-inf" : "inf") : format_number(v); };
    return std::string(lo_open || std::isinf(lo) ? "(" : "[") + end(lo) + ", " + end(hi) +
           (hi_open || std::isinf(hi) ? ")" : "]");
  }
};
Range closed(double lo, double hi) { return {lo, hi, false, false}; }
Range positive(double hi = kInf) { return {0, hi, true, false}; }

// Reads one TOML table into plain structs, remembering which keys it used; finish() rejects the
// rest. Every error names the file and the full dotted key.
class TableReader {
 public:
  TableReader(const toml::table& table, std::string path, const std::string& source)
      : table_(table), path_(std::move(path)), source_(source) {}

  std::string key(const std::string& k) const { return path_.empty() ? k : path_ + "." + k; }
  [[noreturn]] void fail(const std::string& k, const std::string& what) const {
    throw ConfigError(source_, key(k), what);
  }
  bool has(const std::string& k) const { return table_.contains(k); }
  const toml::node* node(const std::string& k) {
    used_.insert(k);
    return table_.get(k);
  }

  void number(const std::string& k, double& out, Range range) {
    const toml::node* n = node(k);
    if (!n) return;
    if (!n->is_number()) fail(k, "expected a number in " + range.text() + ", got " + type_name(*n));
    const double v = n->is_integer() ? static_cast<double>(n->as_integer()->get())
                                     : n->as_floating_point()->get();
    if (!std::isfinite(v) || !range.contains(v))
      fail(k, "value " + format_number(v) + " is out of the allowed range " + range.text());
    out = v;
  }
  template <class Int>
  void integer(const std::string& k, Int& out, double lo, double hi) {
    const toml::node* n = node(k);
    if (!n) return;
    const Range range = closed(lo, hi);
    if (!n->is_integer()) fail(k, "expected an integer in " + range.text() + ", got " + type_name(*n));
    const auto v = n->as_integer()->get();
    if (v < lo || v > hi) fail(k, "value " + std::to_string(v) + " is out of the allowed range " + range.text());
    out = static_cast<Int>(v);
  }
  void boolean(const std::string& k, bool& out) {
    const toml::node* n = node(k);
    if (!n) return;
    if (!n->is_boolean()) fail(k, "expected true or false, got " + type_name(*n));
    out = n->as_boolean()->get();
  }
  void string(const std::string& k, std::string& out) {
    const toml::node* n = node(k);
    if (!n) return;
    if (!n->is_string()) fail(k, "expected a string, got " + type_name(*n));
    out = n->as_string()->get();
  }
  template <class Enum>
  void choice(const std::string& k, Enum& out,
              const std::vector<std::pair<std::string, Enum>>& options) {
    std::string s;
    const bool present = has(k);
    string(k, s);
    if (!present) return;
    std::string allowed;
    for (const auto& [name, value] : options) {
      if (name == s) { out = value; return; }
      allowed += (allowed.empty() ? "" : ", ") + ("\"" + name + "\"");
    }
    fail(k, "\"" + s + "\" is not one of " + allowed);
  }
  const toml::table* subtable(const std::string& k) {
    const toml::node* n = node(k);
    if (!n) return nullptr;
    if (!n->is_table()) fail(k, "expected a table, got " + type_name(*n));
    return n->as_table();
  }
  const toml::array* array(const std::string& k) {
    const toml::node* n = node(k);
    if (!n) return nullptr;
    if (!n->is_array()) fail(k, "expected an array, got " + type_name(*n));
    return n->as_array();
  }
  void finish() const {
    for (auto&& [k, v] : table_) {
      const std::string name(k.str());
      if (!used_.count(name)) fail(name, "unknown key" + suggestion());
    }
  }
  void allow(std::initializer_list<const char*> keys, std::string hint) {
    hint_ = std::move(hint);
    for (auto k : keys) known_.emplace_back(k);
  }

  static std::string type_name(const toml::node& n) {
    switch (n.type()) {
      case toml::node_type::string: return "a string";
      case toml::node_type::integer: return "an integer";
      case toml::node_type::floating_point: return "a number";
      case toml::node_type::boolean: return "a boolean";
      case toml::node_type::array: return "an array";
      case toml::node_type::table: return "a table";
      default: return "a date or time";
    }
  }

 private:
  std::string suggestion() const {
    if (known_.empty()) return "";
    std::string s = " (allowed here: ";
    for (size_t i = 0; i < known_.size(); ++i) s += (i ? ", " : "") + known_[i];
    return s + ")";
  }
  const toml::table& table_;
  std::string path_;
  const std::string& source_;
  std::set<std::string> used_;
  std::vector<std::string> known_;
  std::string hint_;
};

// The contact laws' names come from their registry (contact/registry.hpp).
template <class Laws>
std::vector<std::pair<std::string, std::string>> law_choices() {
  std::vector<std::pair<std::string, std::string>> v;
  for (const auto& name : Laws::names()) v.emplace_back(name, name);
  return v;
}
const std::vector<std::pair<std::string, WallInside>> kWallSides = {
    {"left", WallInside::left}, {"right", WallInside::right}, {"both", WallInside::both}};
const std::vector<std::pair<std::string, SizeDistribution>> kDistributions = {
    {"uniform", SizeDistribution::uniform}, {"lognormal", SizeDistribution::lognormal}};
const std::vector<std::pair<std::string, IntegratorKind>> kIntegrators = {
    {"symplectic_euler", IntegratorKind::symplectic_euler},
    {"velocity_verlet", IntegratorKind::velocity_verlet}};

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

  if (auto t = top.subtable("material")) {
    TableReader r(*t, "material", source);
    r.allow({"density", "friction", "wall_friction", "restitution", "wall_restitution"}, "");
    r.number("density", s.material.density, positive());
    r.number("friction", s.material.friction, closed(0, 100));
    r.number("wall_friction", s.material.wall_friction, closed(0, 100));
    // e_n below 0.01 means nothing numerically: Walton–Braun's loading slope e_n^2 k_U falls
    // under 1e-4 of its unloading one, and the dashpot laws' damping (designed by simulating
    // collisions, derive.cpp) grows without bound as e_n goes to 0.
    r.number("restitution", s.material.restitution, closed(0.01, 1));
    r.number("wall_restitution", s.material.wall_restitution, closed(0.01, 1));
    r.finish();
  }
  if (auto t = top.subtable("contact")) {
    TableReader r(*t, "contact", source);
    r.allow({"normal_model", "tangential_model", "rolling_model", "design_impact_speed",
             "design_max_overlap", "stiffness_ratio", "rolling_friction", "rolling_damping",
             "overlap_guard"}, "");
    r.choice("normal_model", s.contact.normal_model, law_choices<NormalLaws>());
    r.choice("tangential_model", s.contact.tangential_model, law_choices<TangentialLaws>());
    r.choice("rolling_model", s.contact.rolling_model, law_choices<RollingLaws>());
    r.number("rolling_friction", s.contact.rolling_friction, closed(0, 10));
    r.number("rolling_damping", s.contact.rolling_damping, closed(0, 10));
    // A law may be defined only with one normal law (its registry row says which).
    TangentialLaws::with(s.contact.tangential_model, [&](auto law) {
      using Law = decltype(law);
      if constexpr (requires { Law::kNormalLaw; })
        if (s.contact.normal_model != Law::kNormalLaw)
          r.fail("tangential_model", "\"" + s.contact.tangential_model + "\" needs contact.normal_model = \"" +
                                         Law::kNormalLaw + "\" (it is \"" + s.contact.normal_model + "\")");
    });
    r.number("design_impact_speed", s.contact.design_impact_speed, positive(1e6));
    r.number("design_max_overlap", s.contact.design_max_overlap, {0, 0.5, true, false});
    r.number("stiffness_ratio", s.contact.stiffness_ratio, {0, 10, true, false});
    r.number("overlap_guard", s.contact.overlap_guard, {0, 1, true, false});
    r.finish();
  }
  if (auto t = top.subtable("integration")) {
    TableReader r(*t, "integration", source);
    r.allow({"integrator", "dt_fraction", "skin", "gravity"}, "");
    r.choice("integrator", s.integration.integrator, kIntegrators);
    // Below 1e-4 of tau_min a collision takes over 60,000 steps and a run never ends in
    // practice (the stability limit, 1/pi, is checked with the setup).
    r.number("dt_fraction", s.integration.dt_fraction, closed(1e-4, 1));
    r.number("skin", s.integration.skin, {0, 10, true, false});
    r.number("gravity", s.integration.gravity, positive(1e4));
    r.finish();
  }
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

  if (auto t = top.subtable("avalanche")) {
    AvalancheDef a;
    TableReader r(*t, "avalanche", source);
    r.allow({"incline_angle", "incline_length", "pile_width", "floor_length", "wall_height",
             "reference_large_count"}, "");
    r.number("incline_angle", a.incline_angle_deg, {0, 90, true, true});
    r.number("incline_length", a.incline_length, {0, 1e5, false, false});
    r.number("pile_width", a.pile_width, {0, 1e5, true, false});
    r.number("floor_length", a.floor_length, {0, 1e6, true, false});
    r.number("wall_height", a.wall_height, {0, 1e6, true, false});
    r.integer("reference_large_count", a.reference_large_count, 1, 1e6);
    r.finish();
    s.avalanche = a;
    double share = 0;
    for (const auto& sp : s.species) share += sp.area_share;
    if (std::abs(share - 1.0) > 1e-9)
      throw ConfigError(source, "species.*.area_share",
                        "the area shares of an avalanche's species must add up to 1 (they add up to " +
                            format_number(share) + ")");
  }
  if (auto t = top.subtable("preparation")) {
    TableReader r(*t, "preparation", source);
    r.allow({"seed", "initial_packing", "initial_speed", "growth_time", "settle_ek_threshold",
             "settle_hold", "settle_max_time", "damping"}, "");
    std::int64_t seed = static_cast<std::int64_t>(s.preparation.seed);
    r.integer("seed", seed, 0, 9.2e18);
    s.preparation.seed = static_cast<std::uint64_t>(seed);
    r.number("initial_packing", s.preparation.initial_packing, {0, 0.9, true, false});
    r.number("initial_speed", s.preparation.initial_speed, closed(0, 100));
    r.number("growth_time", s.preparation.growth_time, {0, 1e4, true, false});
    r.number("settle_ek_threshold", s.preparation.settle_ek_threshold, {0, 1, true, false});
    r.number("settle_hold", s.preparation.settle_hold, closed(0, 1e4));
    r.number("settle_max_time", s.preparation.settle_max_time, {0, 1e6, true, false});
    r.number("damping", s.preparation.damping, {0, 1, false, true});
    r.finish();
  }
  if (auto t = top.subtable("rest")) {
    TableReader r(*t, "rest", source);
    r.allow({"ek_threshold", "hold", "max_time"}, "");
    r.number("ek_threshold", s.rest.ek_threshold, {0, 1, true, false});
    r.number("hold", s.rest.hold, closed(0, 1e4));
    r.number("max_time", s.rest.max_time, {0, 1e7, true, false});
    r.finish();
  }
  if (auto t = top.subtable("output")) {
    TableReader r(*t, "output", source);
    r.allow({"series", "timeseries_every", "checkpoint_every", "dump_every", "vtk_every", "end_time",
             "basal_layer_packing"}, "");
    if (const toml::array* list = r.array("series")) {
      s.output.series = {false, false, false, false, false};
      for (const auto& item : *list) {
        const auto* name = item.as_string();
        bool SeriesSelection::*flag = nullptr;
        std::string allowed;
        for (const auto& [n, f] : kSeriesNames) {
          if (name && n == name->get()) flag = f;
          allowed += (allowed.empty() ? "\"" : ", \"") + std::string(n) + "\"";
        }
        if (!flag)
          r.fail("series", (name ? "\"" + std::string(name->get()) + "\"" : std::string("an item")) +
                               " is not one of " + allowed);
        s.output.series.*flag = true;
      }
    }
    r.number("timeseries_every", s.output.timeseries_every, {0, 1e6, true, false});
    r.number("checkpoint_every", s.output.checkpoint_every, closed(0, 1e7));
    r.number("dump_every", s.output.dump_every, closed(0, 1e7));
    r.number("vtk_every", s.output.vtk_every, closed(0, 1e7));
    r.number("end_time", s.output.end_time, closed(0, 1e7));
    r.number("basal_layer_packing", s.output.basal_layer_packing, {0, 1, true, false});
    r.finish();
  }

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

namespace {

toml::table physics_tables(const SceneDef& s, bool include_rest) {
  toml::table root;
  root.insert("name", s.name);
  root.insert("material", toml::table{{"density", s.material.density},
                                      {"friction", s.material.friction},
                                      {"wall_friction", s.material.wall_friction},
                                      {"restitution", s.material.restitution},
                                      {"wall_restitution", s.material.wall_restitution}});
  root.insert("contact", toml::table{{"normal_model", s.contact.normal_model},
                                     {"tangential_model", s.contact.tangential_model},
                                     {"rolling_model", s.contact.rolling_model},
                                     {"rolling_friction", s.contact.rolling_friction},
                                     {"rolling_damping", s.contact.rolling_damping},
                                     {"design_impact_speed", s.contact.design_impact_speed},
                                     {"design_max_overlap", s.contact.design_max_overlap},
                                     {"stiffness_ratio", s.contact.stiffness_ratio},
                                     {"overlap_guard", s.contact.overlap_guard}});
  root.insert("integration", toml::table{{"integrator", to_string(s.integration.integrator)},
                                         {"dt_fraction", s.integration.dt_fraction},
                                         {"skin", s.integration.skin},
                                         {"gravity", s.integration.gravity}});
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
    const auto& a = *s.avalanche;
    root.insert("avalanche", toml::table{{"incline_angle", a.incline_angle_deg},
                                         {"incline_length", a.incline_length},
                                         {"pile_width", a.pile_width},
                                         {"floor_length", a.floor_length},
                                         {"wall_height", a.wall_height},
                                         {"reference_large_count", a.reference_large_count}});
    const auto& p = s.preparation;
    root.insert("preparation", toml::table{{"seed", static_cast<std::int64_t>(p.seed)},
                                           {"initial_packing", p.initial_packing},
                                           {"initial_speed", p.initial_speed},
                                           {"growth_time", p.growth_time},
                                           {"settle_ek_threshold", p.settle_ek_threshold},
                                           {"settle_hold", p.settle_hold},
                                           {"settle_max_time", p.settle_max_time},
                                           {"damping", p.damping}});
  }
  if (include_rest) {
    root.insert("rest", toml::table{{"ek_threshold", s.rest.ek_threshold},
                                    {"hold", s.rest.hold},
                                    {"max_time", s.rest.max_time}});
    toml::array series;
    for (const auto& [name, flag] : kSeriesNames)
      if (s.output.series.*flag) series.push_back(name);
    root.insert("output", toml::table{{"series", series},
                                      {"timeseries_every", s.output.timeseries_every},
                                      {"checkpoint_every", s.output.checkpoint_every},
                                      {"dump_every", s.output.dump_every},
                                      {"vtk_every", s.output.vtk_every},
                                      {"end_time", s.output.end_time},
                                      {"basal_layer_packing", s.output.basal_layer_packing}});
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

}  // namespace runout::io

namespace runout::io {

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

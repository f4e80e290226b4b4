#include "runout/io/sweep_file.hpp"

#include <cmath>
#include <sstream>
#include <toml++/toml.h>

#include "runout/errors.hpp"

namespace runout::io {

namespace {

std::string value_text(const toml::node& n) {
  std::ostringstream out;
  if (n.is_string()) out << n.as_string()->get();
  else if (n.is_integer()) out << n.as_integer()->get();
  else if (n.is_floating_point()) out << n.as_floating_point()->get();
  else if (n.is_boolean()) out << (n.as_boolean()->get() ? "true" : "false");
  return out.str();  // tables and arrays are refused before this is asked
}

std::string toml_text(const toml::node& n) {
  if (n.is_string()) {
    std::ostringstream out;
    out << toml::value<std::string>(n.as_string()->get());
    return out.str();
  }
  return value_text(n);
}

double number_of(const toml::node& n, const std::string& source, const std::string& key) {
  if (n.is_integer()) return static_cast<double>(n.as_integer()->get());
  if (n.is_floating_point()) return n.as_floating_point()->get();
  throw ConfigError(source, key, "expected numbers");
}

std::string format(double v) {
  std::ostringstream out;
  out.precision(17);
  out << v;
  return out.str();
}

// Short names for folder names: Dd4_pct40_seed1.
std::string short_name(const std::string& key) {
  if (key == "ratio") return "Dd";
  if (key == "small_share") return "pct";
  if (key == "seed") return "seed";
  return key.substr(key.rfind('.') + 1) + "-";
}

std::string clean(std::string s) {
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '-') c = '-';
  return s;
}

struct Axis {
  std::string key;
  std::vector<std::string> shown;                   // the value as written
  std::vector<std::vector<Override>> overrides;     // per value
};

}  // namespace

SweepDef read_sweep(const std::string& text, const std::string& source, double large_diameter) {
  toml::table root;
  try {
    root = toml::parse(text, source);
  } catch (const toml::parse_error& e) {
    std::ostringstream msg;
    msg << "line " << e.source().begin.line << ", column " << e.source().begin.column << ": " << e.description();
    throw ConfigError(source, "(syntax)", msg.str());
  }
  SweepDef s;
  s.source = source;
  std::string combine = "product";
  bool states_for_all = false;
  for (const auto& [k, v] : root) {
    const std::string key(k.str());
    if (key == "base") {
      if (!v.is_string()) throw ConfigError(source, "base", "expected \"thesis\" or the path of a scene file");
      s.base = v.as_string()->get();
    } else if (key == "combine") {
      if (!v.is_string() || (v.as_string()->get() != "product" && v.as_string()->get() != "zip"))
        throw ConfigError(source, "combine", "expected \"product\" (every combination) or \"zip\" (the axes side by side)");
      combine = v.as_string()->get();
    } else if (key == "pictures") {
      const toml::table* t = v.as_table();
      if (!t) throw ConfigError(source, "pictures", "expected a table [pictures]");
      for (const auto& [pk, pv] : *t) {
        const std::string where = "pictures." + std::string(pk.str());
        if (pk.str() == "strip_times") {
          const toml::array* a = pv.as_array();
          if (!a) throw ConfigError(source, where, "expected a list of t* >= 0 (or [] for none)");
          s.strip_times.clear();
          for (const toml::node& n : *a) {
            const double t_star = number_of(n, source, where);
            if (!(t_star >= 0 && t_star <= 1e6))
              throw ConfigError(source, where, "value " + value_text(n) + " is out of the allowed range [0, 1e6]");
            s.strip_times.push_back(t_star);
          }
        } else if (pk.str() == "seeds") {
          if (!pv.is_string() || (pv.as_string()->get() != "first" && pv.as_string()->get() != "all"))
            throw ConfigError(source, where, "expected \"first\" (the cases of the first seed keep their states) or \"all\"");
          states_for_all = pv.as_string()->get() == "all";
        } else {
          throw ConfigError(source, where, "unknown key (allowed: strip_times, seeds)");
        }
      }
    } else if (key != "axes") {
      throw ConfigError(source, key, "unknown key (allowed: base, combine, axes, pictures)");
    }
  }
  if (s.base.empty()) throw ConfigError(source, "base", "is required: \"thesis\" or the path of a scene file");
  const toml::table* axes = root["axes"].as_table();
  if (!axes || axes->empty()) throw ConfigError(source, "axes", "is required: at least one axis, e.g. seed = [1, 2, 3]");

  std::vector<Axis> list;
  for (const auto& [k, v] : *axes) {
    Axis a;
    a.key = std::string(k.str());
    const std::string where = "axes." + a.key;
    const toml::array* values = v.as_array();
    if (!values) throw ConfigError(source, where, "expected a list of values");
    if (values->empty()) throw ConfigError(source, where, "is empty: give at least one value");
    for (const toml::node& n : *values) {
      if (!n.is_number() && !n.is_string() && !n.is_boolean())
        throw ConfigError(source, where, "expected numbers, strings or booleans");
      std::vector<Override> o;
      if (a.key == "ratio") {
        double r = number_of(n, source, where);
        if (!(r > 1 && r <= 100)) throw ConfigError(source, where, "value " + value_text(n) + " is out of the allowed range (1, 100]");
        if (std::abs(r - 8.33) < 0.005) r = 25.0 / 3.0;  // the thesis's 8.33 is d = 0.12 m (SPEC §5)
        o.push_back({"species.small.diameter", format(large_diameter / r)});
      } else if (a.key == "small_share") {
        const double p = number_of(n, source, where);
        if (!(p >= 0 && p <= 100)) throw ConfigError(source, where, "value " + value_text(n) + " is out of the allowed range [0, 100]");
        o.push_back({"species.small.area_share", format(p / 100)});
        o.push_back({"species.large.area_share", format(1 - p / 100)});
      } else if (a.key == "seed") {
        if (!n.is_integer() || n.as_integer()->get() < 0)
          throw ConfigError(source, where, "expected integers >= 0");
        o.push_back({"preparation.seed", value_text(n)});
      } else {
        if (a.key.find('.') == std::string::npos)
          throw ConfigError(source, where, "unknown axis (allowed: ratio, small_share, seed, or a scene key such as \"contact.design_max_overlap\")");
        o.push_back({a.key, toml_text(n)});
      }
      a.shown.push_back(value_text(n));
      a.overrides.push_back(std::move(o));
    }
    s.axis_keys.push_back(a.key);
    list.push_back(std::move(a));
  }

  if (combine == "zip") {
    for (const Axis& a : list)
      if (a.shown.size() != list.front().shown.size())
        throw ConfigError(source, "axes." + a.key, "has " + std::to_string(a.shown.size()) + " values, " +
                          "but combine = \"zip\" needs every axis as long as axes." + list.front().key +
                          " (" + std::to_string(list.front().shown.size()) + ")");
  }
  std::size_t total = 1;
  if (combine == "zip") total = list.front().shown.size();
  else
    for (const Axis& a : list) {
      total *= a.shown.size();
      if (total > 100000) throw ConfigError(source, "axes", "more than 100,000 cases");
    }
  for (std::size_t c = 0; c < total; ++c) {
    SweepCase k;
    k.keeps_states = !s.strip_times.empty();
    std::size_t rest = c;
    std::vector<std::size_t> pick(list.size());
    for (std::size_t a = list.size(); a-- > 0;) {  // last axis fastest
      pick[a] = combine == "zip" ? c : rest % list[a].shown.size();
      if (combine != "zip") rest /= list[a].shown.size();
    }
    for (std::size_t a = 0; a < list.size(); ++a) {
      const std::string& v = list[a].shown[pick[a]];
      k.axes.emplace_back(list[a].key, v);
      if (!k.name.empty()) k.name += '_';
      k.name += short_name(list[a].key);
      k.name += clean(v);
      for (const Override& o : list[a].overrides[pick[a]]) k.overrides.push_back(o);
      if (list[a].key == "seed" && pick[a] != 0 && !states_for_all) k.keeps_states = false;
    }
    s.cases.push_back(std::move(k));
  }
  return s;
}

}  // namespace runout::io

// Reading one TOML table of a scene strictly: TableReader remembers the keys it was asked for
// and rejects the rest; KeyReader reads a section's keys from their list (scene_keys.hpp).
// Every error names the file and the full dotted key. Internal to runout_io.
#pragma once

#include <toml++/toml.h>

#include <set>
#include <string>
#include <utility>
#include <vector>

#include "runout/errors.hpp"
#include "scene_keys.hpp"

namespace runout::io {

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
  void know(const char* k) { known_.emplace_back(k); }
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
    return s + hint_ + ")";
  }
  const toml::table& table_;
  std::string path_;
  const std::string& source_;
  std::set<std::string> used_;
  std::vector<std::string> known_;
  std::string hint_;
};

// Reads a section's keys, as its list (scene_keys.hpp) names them, through a TableReader.
struct KeyReader {
  TableReader& r;
  void number(const char* k, double& out, Range range, const char*) {
    r.know(k);
    r.number(k, out, range);
  }
  template <class Int>
  void integer(const char* k, Int& out, double lo, double hi, const char*) {
    r.know(k);
    r.integer(k, out, lo, hi);
  }
  template <class T>
  void choice(const char* k, T& out, const Options<T>& options, const char*) {
    r.know(k);
    r.choice(k, out, options);
  }
  template <class Flags, std::size_t N>
  void flags(const char* k, Flags& out, const std::pair<const char*, bool Flags::*> (&names)[N], const char*) {
    r.know(k);
    const toml::array* list = r.array(k);
    if (!list) return;
    for (const auto& [n, f] : names) out.*f = false;
    for (const auto& item : *list) {
      const auto* name = item.as_string();
      bool Flags::*flag = nullptr;
      std::string allowed;
      for (const auto& [n, f] : names) {
        if (name && n == name->get()) flag = f;
        allowed += (allowed.empty() ? "\"" : ", \"") + std::string(n) + "\"";
      }
      if (!flag)
        r.fail(k, (name ? "\"" + std::string(name->get()) + "\"" : std::string("an item")) + " is not one of " + allowed);
      out.*flag = true;
    }
  }
};

// Reads the optional table `name` of `top` through its key list.
template <class List>
void read_section(TableReader& top, const char* name, const std::string& source, List&& list) {
  if (const toml::table* t = top.subtable(name)) {
    TableReader r(*t, name, source);
    KeyReader reader{r};
    list(reader);
    r.finish();
  }
}

}  // namespace runout::io

// Checks for command-line values that CLI11 does not make itself.
#pragma once

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

namespace runout::app {

// A finite real number in [lo, hi]. CLI::Range lets "nan" through (every comparison with NaN
// is false, so NaN lies inside any range), and a NaN cadence would be taken as "not given".
inline CLI::Validator real_in(double lo, double hi) {
  auto text_of = [](double v) {  // 1e7, not 1e+07
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    std::string s = buf;
    if (const auto e = s.find("e+"); e != std::string::npos) s.erase(e + 1, s[e + 2] == '0' ? 2 : 1);
    else if (const auto m = s.find("e-0"); m != std::string::npos) s.erase(m + 2, 1);
    return s;
  };
  const std::string allowed = "[" + text_of(lo) + ", " + text_of(hi) + "]";
  return CLI::Validator(
      [lo, hi, allowed](std::string& text) -> std::string {
        std::size_t used = 0;
        double v = 0;
        try {
          v = std::stod(text, &used);
        } catch (const std::exception&) {
          used = 0;
        }
        if (used == 0 || used != text.size() || !std::isfinite(v) || v < lo || v > hi)
          return "\"" + text + "\" is not a number in " + allowed;
        return {};
      },
      "REAL in " + allowed, "real_in");
}

// A file to be written: its folder exists and the path is not a folder itself, checked before
// any work starts so a long run cannot end unable to write what it measured.
inline CLI::Validator file_to_write() {
  return CLI::Validator(
      [](std::string& path) -> std::string {
        const std::filesystem::path parent = std::filesystem::path(path).parent_path();
        if (!parent.empty() && !std::filesystem::is_directory(parent)) return "folder " + parent.string() + " does not exist";
        if (std::filesystem::is_directory(path)) return path + " is a folder";
        return {};
      },
      "FILE", "file_to_write");
}

}  // namespace runout::app

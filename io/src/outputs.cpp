#include "runout/io/outputs.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>

namespace runout::io {

namespace {

// JSON has no NaN: a quantity that is undefined for this run (no small discs, not at rest) is
// written as null.
// The preparation's report (SPEC §5), in summary.json and beside a cached pile.
nlohmann::json settle_report_object(const SettleReport& s) {
  return {{"t_star_grown", s.t_star_grown},
          {"t_star_settled", s.t_star_settled},
          {"ek_over_ep_undamped", s.ek_over_ep_undamped},
          {"damped_rounds", s.damped_rounds},
          {"peak_impact_overlap", s.peak_impact_overlap}};
}

nlohmann::json number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); }

}  // namespace

std::string summary_json(const RunResult& r, const SummaryContext& c) {
  nlohmann::json j;
  j["scene"] = c.scene_name;
  j["scene_source"] = c.scene_source;
  j["mu_global"] = number(r.mu_global);
  j["H_cm"] = number(r.H_cm);
  j["L_cm"] = number(r.L_cm);
  j["H_cm_over_d"] = number(r.H_cm / c.unit_length);
  j["L_cm_over_d"] = number(r.L_cm / c.unit_length);
  j["H_over_L_front"] = number(r.H_over_L_front);
  j["H_front"] = number(r.H_front);
  j["L_front"] = number(r.L_front);
  j["com_release"] = {number(r.com_release.x()), number(r.com_release.y())};
  j["com_rest"] = {number(r.com_rest.x()), number(r.com_rest.y())};
  j["n_large"] = r.n_large;
  j["n_small"] = r.n_small;
  nlohmann::json counts = nlohmann::json::object();
  for (std::size_t k = 0; k < r.counts.size() && k < c.species_names.size(); ++k)
    counts[c.species_names[k]] = r.counts[k];
  j["counts"] = counts;
  // Segregation class by class: the deposit's mean centre height above the bed per species.
  nlohmann::json heights = nlohmann::json::object();
  for (std::size_t k = 0; k < r.mean_height_over_d.size() && k < c.species_names.size(); ++k)
    heights[c.species_names[k]] = number(r.mean_height_over_d[k]);
  j["mean_height_over_d"] = heights;
  nlohmann::json diameters = nlohmann::json::object();
  for (std::size_t k = 0; k < c.species_diameters.size() && k < c.species_names.size(); ++k)
    diameters[c.species_names[k]] = c.species_diameters[k];
  j["diameters"] = diameters;
  j["at_rest"] = r.at_rest;
  j["reached_end_time"] = r.reached_end_time;  // stopped by output.end_time (or --end-at-last-snapshot)
  j["t_star_rest"] = number(r.t_star_rest);
  j["t_star_end"] = number(r.t_star_end);
  j["steps"] = r.steps;
  j["dt"] = r.dt;
  j["tau_min"] = c.tau_min;
  j["steps_per_t_star"] = c.unit_time / r.dt;
  j["unit_length_d"] = c.unit_length;
  j["unit_time"] = c.unit_time;
  j["ep0"] = number(r.ep0);
  j["peak_ek_over_ep0"] = number(r.peak_ek_over_ep0);
  j["t_star_peak_ek"] = number(r.t_star_peak_ek);
  j["H_layer_over_d"] = number(r.H_layer_over_d);
  j["H_layer_over_d_spread"] = number(r.H_layer_over_d_spread);
  nlohmann::json windows = nlohmann::json::array();
  for (double t : r.basal_layer.thickness) windows.push_back(number(t / c.unit_length));
  j["H_layer_over_d_windows"] = windows;  // L1, 3/4 L1, 1/2 L1, 1/4 L1
  j["deposit_L1"] = number(r.basal_layer.deposit_end - r.basal_layer.deposit_start);
  j["final_basal_spin"] = number(r.final_basal_spin);
  j["max_overlap_over_radius"] = number(r.max_overlap);
  const auto& e = r.final_energy;
  j["energy_over_ep0"] = {{"kinetic", number(e.ek_over_ep0)},
                          {"rotational", number(e.erot_over_ep0)},
                          {"potential", number(e.ep_over_ep0)},
                          {"elastic", number(e.elastic_over_ep0)},
                          {"dissipated_normal", number(e.dissipated_normal_over_ep0)},
                          {"dissipated_friction", number(e.dissipated_friction_over_ep0)},
                          {"dissipated_rolling", number(e.dissipated_rolling_over_ep0)},
                          {"residual", number(e.residual_over_ep0)},
                          {"worst_residual", number(r.worst_energy_residual)}};
  j["wall_seconds"] = r.wall_seconds;
  j["preparation_seconds"] = c.preparation_seconds;
  j["pile_from_cache"] = c.pile_from_cache;
  j["preparation"] = c.settle ? settle_report_object(*c.settle) : nlohmann::json();
  j["particle_steps_per_second"] = r.particle_steps_per_second;
  j["threads"] = c.threads;
  j["threads_fewest"] = r.fewest_threads > 0 ? r.fewest_threads : c.threads;
  j["seed"] = c.seed;
  j["profile_seconds"] = {{"contact_forces", r.profile.contact_forces},
                          {"integrate", r.profile.integrate},
                          {"rebuild", r.profile.rebuild},
                          {"rebuilds", r.profile.rebuilds},
                          {"observers", r.observer_seconds}};
  return j.dump(2) + "\n";
}

std::string settle_report_json(const SettleReport& s) { return settle_report_object(s).dump(2) + "\n"; }

std::optional<SettleReport> read_settle_report(const std::string& text) {
  const nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
  if (j.is_discarded() || !j.is_object()) return std::nullopt;
  try {
    SettleReport s;
    s.t_star_grown = j.at("t_star_grown").get<double>();
    s.t_star_settled = j.at("t_star_settled").get<double>();
    s.ek_over_ep_undamped = j.at("ek_over_ep_undamped").get<double>();
    s.damped_rounds = j.at("damped_rounds").get<int>();
    s.peak_impact_overlap = j.at("peak_impact_overlap").get<double>();
    return s;
  } catch (const nlohmann::json::exception&) {
    return std::nullopt;
  }
}

std::string timeseries_csv(const std::vector<TimeseriesRow>& rows, const SeriesSelection& want) {
  // One column per quantity, only for the series the scene asked for (OutputDef::series).
  struct Column {
    const char* name;
    const char* format;
    double TimeseriesRow::*field;
    bool on;
  };
  const Column columns[] = {
      {"t_star", "%.6f", &TimeseriesRow::t_star, true},
      {"ek_over_ep0", "%.9g", &TimeseriesRow::ek_over_ep0, true},
      {"erot_over_ep0", "%.9g", &TimeseriesRow::erot_over_ep0, true},
      {"x_cm", "%.9g", &TimeseriesRow::x_cm, true},
      {"y_cm", "%.9g", &TimeseriesRow::y_cm, true},
      {"small_mean_height", "%.9g", &TimeseriesRow::small_mean_height, want.segregation},
      {"large_mean_height", "%.9g", &TimeseriesRow::large_mean_height, want.segregation},
      {"basal_spin", "%.9g", &TimeseriesRow::basal_spin, want.basal_spin},
      {"front_x", "%.9g", &TimeseriesRow::front_x, want.front},
      {"ep_over_ep0", "%.9g", &TimeseriesRow::ep_over_ep0, want.energy},
      {"elastic_over_ep0", "%.9g", &TimeseriesRow::elastic_over_ep0, want.energy},
      {"dissipated_normal_over_ep0", "%.9g", &TimeseriesRow::dissipated_normal_over_ep0, want.energy},
      {"dissipated_friction_over_ep0", "%.9g", &TimeseriesRow::dissipated_friction_over_ep0, want.energy},
      {"dissipated_rolling_over_ep0", "%.9g", &TimeseriesRow::dissipated_rolling_over_ep0, want.energy},
      {"residual_over_ep0", "%.3e", &TimeseriesRow::residual_over_ep0, want.energy},
      {"max_overlap", "%.4g", &TimeseriesRow::max_overlap, want.overlap},
  };
  std::string out;
  for (const auto& c : columns)
    if (c.on) {
      if (!out.empty()) out += ',';
      out += c.name;
    }
  out += "\n";
  char cell[64];
  for (const auto& r : rows) {
    bool first = true;
    for (const auto& c : columns) {
      if (!c.on) continue;
      // An undefined value (NaN, or a ratio to an Ep0 of zero) is an empty field, which every
      // CSV reader takes as missing; never "nan" or "inf".
      const double v = r.*c.field;
      if (std::isfinite(v)) std::snprintf(cell, sizeof cell, c.format, v);
      else cell[0] = '\0';
      if (!first) out += ',';
      out += cell;
      first = false;
    }
    out += '\n';
  }
  return out;
}

std::string lammps_dump_frame(const World& world, double t_star) {
  const auto& p = world.particles();
  double xlo = 0, xhi = 0, ylo = 0, yhi = 0;
  bool first = true;
  auto grow = [&](double x, double y) {
    if (first) { xlo = xhi = x; ylo = yhi = y; first = false; }
    xlo = std::min(xlo, x); xhi = std::max(xhi, x); ylo = std::min(ylo, y); yhi = std::max(yhi, y);
  };
  for (const auto& s : world.segments()) { grow(s.a.x(), s.a.y()); grow(s.b.x(), s.b.y()); }
  for (std::size_t k = 0; k < p.size(); ++k) {
    grow(p.x[k] - p.radius[k], p.y[k] - p.radius[k]);
    grow(p.x[k] + p.radius[k], p.y[k] + p.radius[k]);
  }
  std::string out;
  out.reserve(p.size() * 96 + 256);
  char line[256];
  // TIME before TIMESTEP, as LAMMPS's own `dump_modify time yes` writes it: its read_dump
  // refuses the other order ("Dump file is incorrectly formatted"); OVITO and ASE read either.
  std::snprintf(line, sizeof line, "ITEM: TIME\n%.9g\nITEM: TIMESTEP\n%lld\n", t_star,
                static_cast<long long>(world.step_count()));
  out += line;
  std::snprintf(line, sizeof line, "ITEM: NUMBER OF ATOMS\n%zu\n", p.size());
  out += line;
  double rmax = 0;
  for (double r : p.radius) rmax = std::max(rmax, r);
  std::snprintf(line, sizeof line, "ITEM: BOX BOUNDS ff ff pp\n%.9g %.9g\n%.9g %.9g\n%.9g %.9g\n",
                xlo, xhi, ylo, yhi, -rmax, rmax);
  out += line;
  // z and vz (always 0) are there for ASE: its lammps-dump-text reader takes positions and
  // velocities only as whole x y z and vx vy vz triples, and without z it builds no atoms at all
  // (LAMMPS's read_dump of a 2D box reads x y vx vy and skips the other columns).
  out += "ITEM: ATOMS id type x y z radius vx vy vz omegaz\n";
  for (std::size_t k = 0; k < p.size(); ++k) {
    std::snprintf(line, sizeof line, "%lld %d %.9g %.9g 0 %.9g %.9g %.9g 0 %.9g\n",
                  static_cast<long long>(p.id[k]), p.species[k] + 1, p.x[k], p.y[k], p.radius[k],
                  p.vx[k], p.vy[k], p.omega[k]);
    out += line;
  }
  return out;
}

}  // namespace runout::io

namespace runout::io {

namespace {

// The appended block of a VTK XML file: each array a UInt64 byte count and its values, little
// endian whatever the machine (the header says byte_order="LittleEndian").
class AppendedData {
 public:
  // Adds an array and returns its offset, counted from the first byte after the '_' marker.
  template <class T>
  std::size_t add(const std::vector<T>& values) {
    const std::size_t offset = bytes_.size();
    put(static_cast<std::uint64_t>(values.size() * sizeof(T)));
    for (const T& v : values) put(v);
    return offset;
  }
  const std::string& bytes() const { return bytes_; }

 private:
  template <class T>
  void put(T v) {
    char raw[sizeof(T)];
    std::memcpy(raw, &v, sizeof(T));
    if constexpr (std::endian::native == std::endian::big) std::reverse(raw, raw + sizeof(T));
    bytes_.append(raw, sizeof(T));
  }
  std::string bytes_;
};

std::string nine_digits(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v);  // as the dump's TIME: 9 significant digits
  return buf;
}

}  // namespace

std::string vtk_polydata_frame(const World& world, double t_star, const std::vector<char>& basal_layer) {
  const auto& p = world.particles();
  const std::size_t n = p.size();
  std::vector<const Segment*> walls;
  for (const auto& s : world.segments())
    if (s.active) walls.push_back(&s);  // a released gate is no longer drawn, nor exported
  const std::size_t points = n + 2 * walls.size();

  std::vector<double> xyz, radius(points, 0.0), velocity(3 * points, 0.0), spin(points, 0.0);
  std::vector<std::int32_t> species(points, -1);
  std::vector<std::uint8_t> basal(points, 0);
  std::vector<std::int64_t> id(points, -1);
  xyz.reserve(3 * points);
  for (std::size_t k = 0; k < n; ++k) {
    xyz.insert(xyz.end(), {p.x[k], p.y[k], 0.0});
    radius[k] = p.radius[k];
    velocity[3 * k] = p.vx[k];
    velocity[3 * k + 1] = p.vy[k];
    spin[k] = p.omega[k];
    species[k] = p.species[k];
    basal[k] = k < basal_layer.size() && basal_layer[k] ? 1 : 0;
    id[k] = p.id[k];
  }
  for (const Segment* s : walls) xyz.insert(xyz.end(), {s->a.x(), s->a.y(), 0.0, s->b.x(), s->b.y(), 0.0});
  // Cells: a vertex per disc (so ParaView shows the discs as points without a filter) and a
  // line per wall; offsets are each cell's end in the connectivity list.
  std::vector<std::int64_t> vert_conn(n), vert_offsets(n), line_conn(2 * walls.size()), line_offsets(walls.size());
  for (std::size_t k = 0; k < n; ++k) {
    vert_conn[k] = static_cast<std::int64_t>(k);
    vert_offsets[k] = static_cast<std::int64_t>(k + 1);
  }
  for (std::size_t w = 0; w < walls.size(); ++w) {
    line_conn[2 * w] = static_cast<std::int64_t>(n + 2 * w);
    line_conn[2 * w + 1] = static_cast<std::int64_t>(n + 2 * w + 1);
    line_offsets[w] = static_cast<std::int64_t>(2 * (w + 1));
  }

  AppendedData data;
  auto array = [&](const char* type, const char* name, int components, std::size_t offset) {
    char buf[200];
    std::snprintf(buf, sizeof buf,
                  "        <DataArray type=\"%s\" Name=\"%s\" NumberOfComponents=\"%d\" format=\"appended\" "
                  "offset=\"%zu\"/>\n",
                  type, name, components, offset);
    return std::string(buf);
  };
  std::string xml;
  xml += "<?xml version=\"1.0\"?>\n";
  xml += "<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n";
  xml += "  <PolyData>\n    <FieldData>\n";
  xml += "      <DataArray type=\"Float64\" Name=\"TimeValue\" NumberOfTuples=\"1\" format=\"ascii\">" +
         nine_digits(t_star) + "</DataArray>\n";
  xml += "      <DataArray type=\"Int64\" Name=\"step\" NumberOfTuples=\"1\" format=\"ascii\">" +
         std::to_string(world.step_count()) + "</DataArray>\n";
  xml += "    </FieldData>\n";
  xml += "    <Piece NumberOfPoints=\"" + std::to_string(points) + "\" NumberOfVerts=\"" + std::to_string(n) +
         "\" NumberOfLines=\"" + std::to_string(walls.size()) + "\" NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n";
  xml += "      <PointData Scalars=\"species\" Vectors=\"velocity\">\n";
  xml += array("Float64", "radius", 1, data.add(radius));
  xml += array("Float64", "velocity", 3, data.add(velocity));
  xml += array("Float64", "spin", 1, data.add(spin));
  xml += array("Int32", "species", 1, data.add(species));
  xml += array("UInt8", "basal_layer", 1, data.add(basal));
  xml += array("Int64", "id", 1, data.add(id));
  xml += "      </PointData>\n      <Points>\n";
  xml += array("Float64", "Points", 3, data.add(xyz));
  xml += "      </Points>\n      <Verts>\n";
  xml += array("Int64", "connectivity", 1, data.add(vert_conn));
  xml += array("Int64", "offsets", 1, data.add(vert_offsets));
  xml += "      </Verts>\n      <Lines>\n";
  xml += array("Int64", "connectivity", 1, data.add(line_conn));
  xml += array("Int64", "offsets", 1, data.add(line_offsets));
  xml += "      </Lines>\n    </Piece>\n  </PolyData>\n";
  xml += "  <AppendedData encoding=\"raw\">\n   _";
  xml += data.bytes();
  xml += "\n  </AppendedData>\n</VTKFile>\n";
  return xml;
}

std::optional<double> vtk_frame_time(std::string_view head) {
  const std::string_view key = "Name=\"TimeValue\"";
  const auto at = head.find(key);
  if (at == std::string_view::npos) return std::nullopt;
  const auto open = head.find('>', at), close = head.find('<', at);
  if (open == std::string_view::npos || close == std::string_view::npos || close <= open) return std::nullopt;
  const std::string text(head.substr(open + 1, close - open - 1));
  char* end = nullptr;
  const double t = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || *end != '\0' || !std::isfinite(t)) return std::nullopt;
  return t;
}

std::string vtk_collection(const std::vector<VtkCollectionEntry>& frames) {
  std::string xml = "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
                    "  <Collection>\n";
  for (const auto& f : frames)
    xml += "    <DataSet timestep=\"" + nine_digits(f.t_star) + "\" group=\"\" part=\"0\" file=\"" + f.file + "\"/>\n";
  xml += "  </Collection>\n</VTKFile>\n";
  return xml;
}

}  // namespace runout::io

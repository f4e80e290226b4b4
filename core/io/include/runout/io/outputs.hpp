// What a run writes: summary.json, timeseries.csv, LAMMPS `dump custom` frames (OVITO opens
// them). Pure formatting; writing goes through write_file_atomically.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "runout/run.hpp"
#include "runout/setup.hpp"

namespace runout::io {

struct SummaryContext {
  std::string scene_name;
  std::string scene_source;
  double unit_length = 0;  // d, m
  double unit_time = 0;    // s per t*
  double tau_min = 0;
  int threads = 1;
  std::uint64_t seed = 0;
  bool pile_from_cache = false;
  double preparation_seconds = 0;
  std::optional<SettleReport> settle;  // an avalanche pile settled by this run or cached with it
  std::vector<std::string> species_names;
  std::vector<double> species_diameters;  // nominal, m (a size class: the geometric mean of its bounds)
};

std::string summary_json(const RunResult& r, const SummaryContext& c);
// The preparation's report as JSON (summary.json's "preparation", and the pile cache's record
// beside each pile); reading returns nothing for text that is not such a record.
std::string settle_report_json(const SettleReport& s);
std::optional<SettleReport> read_settle_report(const std::string& text);
std::string timeseries_csv(const std::vector<TimeseriesRow>& rows, const SeriesSelection& want = {});
// One frame: ITEM: TIME (t*), TIMESTEP, ... ATOMS id type x y z radius vx vy vz omegaz (z = vz = 0;
// type = species + 1, the species in name order). Read by OVITO, ASE and LAMMPS's read_dump.
std::string lammps_dump_frame(const World& world, double t_star);

}  // namespace runout::io

// What a run writes: summary.json, timeseries.csv, LAMMPS `dump custom` frames (OVITO opens
// them). Pure formatting; writing goes through write_file_atomically.
#pragma once

#include <optional>
#include <string>
#include <string_view>
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

// One VTK XML PolyData frame (.vtp, ParaView), appended raw binary with UInt64 block headers.
// Points: the disc centres (z = 0), then both end points of each active wall. Cells: a vertex
// per disc and a line per wall. Point data: radius (m), velocity (m/s, 3 components, vz = 0),
// spin (omega, rad/s), species (its place in name order, from 0), basal_layer (0/1, from
// `basal_layer`, one entry per disc), id; on wall points radius, velocity, spin and
// basal_layer are 0, species and id -1. Field data: TimeValue (t*), which ParaView reads as
// the frame's time, and step.
std::string vtk_polydata_frame(const World& world, double t_star, const std::vector<char>& basal_layer);
// The t* a frame of vtk_polydata_frame says it shows, read from its opening bytes (its
// TimeValue); nothing for other text.
std::optional<double> vtk_frame_time(std::string_view frame_head);
// A ParaView collection (.pvd) of frames: each file (relative to the .pvd) with its t*.
struct VtkCollectionEntry {
  double t_star = 0;
  std::string file;
};
std::string vtk_collection(const std::vector<VtkCollectionEntry>& frames);

}  // namespace runout::io

#include "runout/checkpoint.hpp"

#include <cmath>
#include <string_view>
#include <type_traits>

#include "runout/errors.hpp"

namespace runout {

namespace {

constexpr char kMagic[8] = {'R', 'U', 'N', 'O', 'U', 'T', 'C', 'K'};

std::uint64_t checksum(std::string_view bytes) {
  std::uint64_t h = 14695981039346656037ull;
  for (unsigned char c : bytes) { h ^= c; h *= 1099511628211ull; }
  return h;
}

// Every value a World relies on, checked before it is built: a checksum only says the bytes
// are the ones written, not that they were sane (a NaN coordinate would reach the cell grid).
void check_state(const Particles& p, const std::string& name) {
  auto bad = [&](const std::string& what, std::size_t k) {
    throw IoError(name + ": checkpoint is corrupt (" + what + " of disc " + std::to_string(k) + ")");
  };
  // Field by field from the discs' one field list (Particles::for_each_stored), so a field
  // added there is checked too: every number finite; sizes, masses and inertias positive (and
  // a mass whose inverse is finite); a species an index.
  Particles::for_each_stored(p, [&](std::string_view field, const auto& v) {
    using Value = typename std::decay_t<decltype(v)>::value_type;
    const bool positive = field == "radius" || field == "mass" || field == "inv_inertia";
    const std::string what = field == "inv_inertia"                ? std::string("moment of inertia")
                             : positive || field == "species"     ? std::string(field)
                                                                  : std::string("a non-finite position, velocity or acceleration");
    for (std::size_t k = 0; k < v.size(); ++k) {
      if constexpr (std::is_floating_point_v<Value>) {
        const bool sane = std::isfinite(v[k]) && (!positive || v[k] > 0) &&
                          (field != "mass" || std::isfinite(1.0 / v[k]));
        if (!sane) bad(what, k);
      } else if (field == "species" && v[k] < 0) {
        bad(what, k);
      }
    }
  });
}

// A contact list is rows of strictly increasing keys, one row per disc; pair keys are discs
// after the row's own, wall keys are segments of the scene.
template <class Contacts>
void check_rows(const HotArray<std::int32_t>& row, const HotArray<std::int32_t>& key,
                const Contacts& c, std::size_t n, std::int64_t key_end, bool pair_rows,
                const std::string& name) {
  auto bad = [&] { throw IoError(name + ": checkpoint is corrupt (contact lists)"); };
  if (row.size() != n + 1 || row[0] != 0 || c.history_width < 0 ||
      c.history.size() != key.size() * static_cast<std::size_t>(c.history_width))
    bad();
  for (std::size_t k = 0; k < n; ++k) {
    if (row[k + 1] < row[k]) bad();
    if (static_cast<std::size_t>(row[k + 1]) > key.size()) bad();
    const std::int64_t first = pair_rows ? static_cast<std::int64_t>(k) + 1 : 0;
    for (std::int32_t q = row[k]; q < row[k + 1]; ++q)
      if (key[q] < first || key[q] >= key_end || (q > row[k] && key[q] <= key[q - 1])) bad();
  }
  if (static_cast<std::size_t>(row[n]) != key.size()) bad();
  for (double v : c.history) if (!std::isfinite(v)) bad();
}

// A contact list as a checkpoint keeps it (pairs: partner j; walls: the segment): rows,
// partners, history width, history. A world that has not stepped yet has no lists: empty rows
// for every disc.
template <class Contacts>
void put_contacts(ByteWriter& w, const Contacts& c, const HotArray<std::int32_t>& partner, std::size_t discs) {
  const bool built = c.row_start.size() == discs + 1;
  w.put_vector(built ? c.row_start : HotArray<std::int32_t>(discs + 1, 0));
  w.put_vector(built ? partner : HotArray<std::int32_t>{});
  w.put<std::int32_t>(c.history_width);
  w.put_vector(built ? c.history : HotArray<double>{});
}
template <class Contacts>
void get_contacts(ByteReader& r, Contacts& c, HotArray<std::int32_t>& partner) {
  c.row_start = r.get_vector<std::int32_t, HotArray<std::int32_t>>();
  partner = r.get_vector<std::int32_t, HotArray<std::int32_t>>();
  c.history_width = r.get<std::int32_t>();
  c.history = r.get_vector<double, HotArray<double>>();
}

}  // namespace

std::string seal_checkpoint(std::string_view payload) {
  std::string out(kMagic, sizeof(kMagic));
  ByteWriter head;
  head.put(kCheckpointVersion);
  head.put<std::uint64_t>(payload.size());
  out += head.bytes();
  out += payload;
  ByteWriter tail;
  tail.put(checksum(payload));
  out += tail.bytes();
  return out;
}

void ByteReader::fail() { throw IoError(name_ + ": checkpoint is truncated or corrupt"); }

std::string encode_checkpoint(const World& world, std::uint64_t scene_key,
                              std::string_view run_state) {
  ByteWriter w;
  const Particles& p = world.particles();
  w.put(scene_key);
  w.put(world.time());
  w.put(world.step_count());
  w.put(world.dissipation().normal);
  w.put(world.dissipation().friction);
  w.put(world.dissipation().rolling);
  Particles::for_each_stored(p, [&](const char*, const auto& v) { w.put_vector(v); });
  std::vector<std::uint8_t> active;
  for (const auto& s : world.segments()) active.push_back(s.active ? 1 : 0);
  w.put_vector(active);
  put_contacts(w, world.pairs(), world.pairs().j, p.size());
  put_contacts(w, world.wall_contacts(), world.wall_contacts().segment, p.size());
  w.put_string(run_state);
  return seal_checkpoint(w.bytes());
}

Checkpoint read_checkpoint(std::string_view bytes, std::uint64_t scene_key, const std::string& name) {
  if (bytes.size() < sizeof(kMagic) + 4 + 8 + 8 ||
      std::string_view(bytes.data(), sizeof(kMagic)) != std::string_view(kMagic, sizeof(kMagic)))
    throw IoError(name + ": not a runout checkpoint");
  ByteReader head(bytes.substr(sizeof(kMagic)), name);
  const auto version = head.get<std::uint32_t>();
  if (version != kCheckpointVersion)
    throw IoError(name + ": checkpoint version " + std::to_string(version) +
                  " is not supported (this runout reads version " +
                  std::to_string(kCheckpointVersion) + ")");
  const auto size = head.get<std::uint64_t>();
  const std::size_t start = sizeof(kMagic) + 4 + 8;
  if (bytes.size() != start + size + 8) throw IoError(name + ": checkpoint is truncated");
  const std::string_view payload = bytes.substr(start, size);
  ByteReader tail(bytes.substr(start + size), name);
  if (tail.get<std::uint64_t>() != checksum(payload))
    throw IoError(name + ": checkpoint checksum mismatch (the file is corrupt)");

  ByteReader r(payload, name);
  if (r.get<std::uint64_t>() != scene_key)
    throw IoError(name + ": checkpoint was written for a different scene");
  Checkpoint c;
  c.time = r.get<double>();
  c.steps = r.get<std::int64_t>();
  c.dissipation.normal = r.get<double>();
  c.dissipation.friction = r.get<double>();
  c.dissipation.rolling = r.get<double>();
  if (!std::isfinite(c.time) || c.time < 0 || c.steps < 0 || !std::isfinite(c.dissipation.normal) ||
      !std::isfinite(c.dissipation.friction) || !std::isfinite(c.dissipation.rolling))
    throw IoError(name + ": checkpoint is corrupt (clock or energy ledger)");
  Particles& p = c.discs;
  Particles::for_each_stored(p, [&](const char*, auto& v) {
    using Vector = std::decay_t<decltype(v)>;
    v = r.get_vector<typename Vector::value_type, Vector>();
  });
  const std::size_t n = p.x.size();
  Particles::for_each_stored(p, [&](const char* field, const auto& v) {
    if (v.size() != n) throw IoError(name + ": checkpoint is corrupt (" + field + " has another length than x)");
  });
  check_state(p, name);
  p.inv_mass.resize(n);
  for (std::size_t k = 0; k < n; ++k) p.inv_mass[k] = 1.0 / p.mass[k];

  c.active_segments = r.get_vector<std::uint8_t>();
  get_contacts(r, c.pairs, c.pairs.j);
  get_contacts(r, c.walls, c.walls.segment);
  c.run_state = r.get_string();
  if (!r.done()) throw IoError(name + ": checkpoint has trailing bytes");
  check_rows(c.pairs.row_start, c.pairs.j, c.pairs, n, static_cast<std::int64_t>(n), true, name);
  return c;
}

World restore_world(Checkpoint c, std::vector<Segment> segments, ContactTable table, StepSettings settings,
                    const std::string& name) {
  // What the scene decides: the species, the walls and the contact laws' history.
  const std::size_t n = c.discs.size();
  for (std::size_t k = 0; k < n; ++k)
    if (c.discs.species[k] >= table.species_count)
      throw IoError(name + ": checkpoint is corrupt (species of disc " + std::to_string(k) + ")");
  if (c.active_segments.size() != segments.size())
    throw IoError(name + ": checkpoint has a different number of walls than the scene");
  check_rows(c.walls.row_start, c.walls.segment, c.walls, n, static_cast<std::int64_t>(segments.size()), false,
             name);
  World world(std::move(c.discs), std::move(segments), std::move(table), std::move(settings));
  // Lists written before the first step are empty; written ones carry the contact model's
  // history, which must be this world's (the scene key covers the laws; this is the proof).
  for (int width : {c.pairs.history_width, c.walls.history_width})
    if (width != 0 && width != world.history_width())
      throw IoError(name + ": checkpoint was written with other contact laws (" +
                    std::to_string(width) + " history values per contact, this scene keeps " +
                    std::to_string(world.history_width()) + ")");
  for (std::size_t s = 0; s < c.active_segments.size(); ++s)
    if (!c.active_segments[s]) world.deactivate_wall_segment(s);
  world.set_clock(c.time, c.steps);
  world.set_dissipation(c.dissipation);
  world.restore_history(c.pairs, c.walls);
  return world;
}

std::string decode_checkpoint(std::string_view bytes, std::uint64_t scene_key, World& world,
                              const std::string& name) {
  Checkpoint c = read_checkpoint(bytes, scene_key, name);
  std::string run_state = std::move(c.run_state);
  world = restore_world(std::move(c), world.segments(), world.table(), world.settings(), name);
  return run_state;
}

}  // namespace runout

// Checkpoints: the dynamic state of a World (discs, clock, removed walls, contact history) plus
// an opaque blob for the caller's run state, in a versioned little-endian binary with an FNV-1a
// checksum. The static parts (walls, coefficients) come from the scene, whose key is stored and
// checked so a checkpoint is never resumed under another scene.
#pragma once

#include <cstdint>
#include <cstring>
#include <vector>
#include <string>
#include <string_view>

#include "runout/world.hpp"

namespace runout {

inline constexpr std::uint32_t kCheckpointVersion = 5;

std::string encode_checkpoint(const World& world, std::uint64_t scene_key,
                              std::string_view run_state);

// Wraps a payload in the magic, version, size and checksum (what encode_checkpoint does last);
// tests and fuzz targets use it to build well-sealed files with chosen contents.
std::string seal_checkpoint(std::string_view payload);

// A checkpoint's contents, read and checked on their own: the format, the checksum, the scene
// key, finite and consistent values. What depends on the scene is checked by restore_world.
struct Checkpoint {
  double time = 0;
  std::int64_t steps = 0;
  Dissipation dissipation;
  Particles discs;
  std::vector<std::uint8_t> active_segments;  // per wall segment of the scene
  PairContacts pairs;                          // rows, partners and history only
  WallContacts walls;
  std::string run_state;                       // the caller's blob
};
// Throws IoError for a corrupt, truncated, foreign or other-version file and for a scene-key
// mismatch (`name` says which file).
Checkpoint read_checkpoint(std::string_view bytes, std::uint64_t scene_key, const std::string& name);

// The World of a checkpoint, made once from its scene's walls, coefficients and settings.
// Throws IoError where the checkpoint does not fit them (species, walls, contact laws).
World restore_world(Checkpoint checkpoint, std::vector<Segment> segments, ContactTable table,
                    StepSettings settings, const std::string& name);

// Both at once into `world`, a World of the same scene (the renderer, tests); returns the
// run-state blob.
std::string decode_checkpoint(std::string_view bytes, std::uint64_t scene_key, World& world,
                              const std::string& name);

// Little helpers to pack plain values and vectors (used for run states too).
class ByteWriter {
 public:
  template <class T> void put(const T& v) {
    out_.append(reinterpret_cast<const char*>(&v), sizeof(T));
  }
  template <class T, class Allocator> void put_vector(const std::vector<T, Allocator>& v) {
    put<std::uint64_t>(v.size());
    if (!v.empty()) out_.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  }
  void put_string(std::string_view s) {
    put<std::uint64_t>(s.size());
    out_.append(s);
  }
  std::string& bytes() { return out_; }

 private:
  std::string out_;
};

class ByteReader {
 public:
  ByteReader(std::string_view in, std::string name) : in_(in), name_(std::move(name)) {}
  template <class T> T get() {
    need(sizeof(T));
    T v;
    std::memcpy(&v, in_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return v;
  }
  // Into a std::vector<T> or another vector of T (HotArray).
  template <class T, class Vector = std::vector<T>> Vector get_vector() {
    const auto n = get<std::uint64_t>();
    if (n > (in_.size() - at_) / sizeof(T)) fail();
    Vector v(n);
    if (n > 0) std::memcpy(v.data(), in_.data() + at_, n * sizeof(T));  // data() may be null when empty
    at_ += n * sizeof(T);
    return v;
  }
  std::string get_string() {
    const auto n = get<std::uint64_t>();
    need(n);
    std::string s(in_.substr(at_, n));
    at_ += n;
    return s;
  }
  bool done() const { return at_ == in_.size(); }

 private:
  void need(std::size_t n) { if (n > in_.size() - at_) fail(); }
  [[noreturn]] void fail();
  std::string_view in_;
  std::size_t at_ = 0;
  std::string name_;
};

}  // namespace runout

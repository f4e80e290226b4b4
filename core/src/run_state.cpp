// The run state's checkpoint codec: RunState::for_each_stored is the one list of its fields.
#include "runout/run_state.hpp"

#include <cmath>
#include <type_traits>

#include "runout/checkpoint.hpp"
#include "runout/errors.hpp"

namespace runout {

namespace {

// One stored value of a run state (RunState::for_each_stored) into a checkpoint's bytes.
template <class T>
void put_field(ByteWriter& w, const T& v) {
  if constexpr (std::is_same_v<T, bool>) w.put(static_cast<std::uint8_t>(v));
  else if constexpr (requires { v.size(); }) w.put_vector(v);
  else w.put(v);
}
template <class T>
void get_field(ByteReader& r, T& v) {
  if constexpr (std::is_same_v<T, bool>) v = r.get<std::uint8_t>() != 0;
  else if constexpr (requires { v.size(); }) v = r.get_vector<typename T::value_type>();
  else v = r.get<T>();
}

}  // namespace

std::string encode_run_state(const RunState& s) {
  ByteWriter w;
  auto put = [&](const char*, const auto& v, bool) { put_field(w, v); };
  RunState::for_each_stored(s, put);
  if (s.rest_frozen) {
    RunState::for_each_stored_at_rest(s, put);
    Particles::for_each_deposit(s.rest_particles, [&](const char*, const auto& v) { w.put_vector(v); });
  }
  return w.bytes();
}

RunState decode_run_state(const std::string& bytes, const std::string& name) {
  ByteReader r(bytes, name);
  RunState s;
  auto corrupt = [&](const std::string& what) { throw IoError(name + ": checkpoint is corrupt (" + what + ")"); };
  // The samples may hold undefined measurements (NaN, written as empty); the run's own
  // bookkeeping may not.
  auto get = [&](const char*, auto& v, bool bookkeeping) {
    get_field(r, v);
    if constexpr (std::is_same_v<std::decay_t<decltype(v)>, double>)
      if (bookkeeping && !std::isfinite(v)) corrupt("run state");
  };
  RunState::for_each_stored(s, get);
  if (s.series_ends_with_end_row && s.series.empty()) corrupt("time series");
  if (s.rest_frozen) {
    RunState::for_each_stored_at_rest(s, get);
    Particles& p = s.rest_particles;
    Particles::for_each_deposit(p, [&](const char*, auto& v) {
      using Vector = std::decay_t<decltype(v)>;
      v = r.get_vector<typename Vector::value_type, Vector>();
    });
    Particles::for_each_deposit(p, [&](const char*, const auto& v) {
      if (v.size() != p.x.size()) corrupt("deposit at rest");
      if constexpr (std::is_same_v<typename std::decay_t<decltype(v)>::value_type, double>)
        for (double x : v)
          if (!std::isfinite(x)) corrupt("deposit at rest");
    });
  }
  if (s.ep0 < 0) corrupt("run state");
  return s;
}

}  // namespace runout

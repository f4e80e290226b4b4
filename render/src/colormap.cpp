#include "runout/render/colormap.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace runout::render {

namespace {

template <std::size_t N>
Rgba interpolate(const std::array<std::array<double, 3>, N>& stops, double t) {
  t = std::clamp(t, 0.0, 1.0);
  const double x = t * (N - 1);
  const std::size_t k = std::min<std::size_t>(static_cast<std::size_t>(x), N - 2);
  const double w = x - k;
  auto channel = [&](int c) {
    return static_cast<std::uint8_t>(std::lround(255.0 * ((1 - w) * stops[k][c] + w * stops[k + 1][c])));
  };
  return {channel(0), channel(1), channel(2), 255};
}

// matplotlib viridis at t = 0, 0.1, ..., 1 (van der Walt and Smith, CC0).
constexpr std::array<std::array<double, 3>, 11> kViridis{{
    {0.267004, 0.004874, 0.329415}, {0.282623, 0.140926, 0.457517},
    {0.253935, 0.265254, 0.529983}, {0.206756, 0.371758, 0.553117},
    {0.163625, 0.471133, 0.558148}, {0.127568, 0.566949, 0.550556},
    {0.134692, 0.658636, 0.517649}, {0.266941, 0.748751, 0.440573},
    {0.477504, 0.821444, 0.318195}, {0.741388, 0.873449, 0.149561},
    {0.993248, 0.906157, 0.143936}}};

// ColorBrewer RdBu end and mid colours, with a light grey centre.
constexpr std::array<std::array<double, 3>, 5> kDiverging{{
    {5 / 255.0, 48 / 255.0, 97 / 255.0}, {67 / 255.0, 147 / 255.0, 195 / 255.0},
    {221 / 255.0, 221 / 255.0, 221 / 255.0}, {214 / 255.0, 96 / 255.0, 77 / 255.0},
    {103 / 255.0, 0.0, 31 / 255.0}}};

}  // namespace

Rgba viridis(double t) { return interpolate(kViridis, t); }
Rgba diverging(double t) { return interpolate(kDiverging, 0.5 * (t + 1.0)); }

}  // namespace runout::render

// Colours for discs: a colour-blind-safe species pair (Okabe–Ito), viridis for magnitudes and a
// diverging map for signed values. Pure functions.
#pragma once

#include "runout/render/image.hpp"

namespace runout::render {

namespace palette {
inline constexpr Rgba kLarge{0, 114, 178, 255};       // Okabe–Ito blue
inline constexpr Rgba kSmall{213, 94, 0, 255};        // Okabe–Ito vermilion
inline constexpr Rgba kOther{0, 158, 115, 255};       // Okabe–Ito bluish green (third species)
inline constexpr Rgba kMutedLarge{198, 208, 218, 255};
inline constexpr Rgba kMutedSmall{238, 206, 180, 255};
inline constexpr Rgba kWall{51, 51, 51, 255};
inline constexpr Rgba kBackground{255, 255, 255, 255};
inline constexpr Rgba kInk{30, 30, 30, 255};          // text, scale bar, frames
}  // namespace palette

// t in [0, 1] (clamped): matplotlib's viridis (CC0), linear between 11 published stops.
Rgba viridis(double t);
// t in [-1, 1] (clamped): dark blue (-1) through light grey (0) to dark red (+1); the grey
// keeps a zero value visible on a white background.
Rgba diverging(double t);

}  // namespace runout::render

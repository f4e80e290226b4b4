// The overlays of a frame: the t* stamp, the scale bar in units of D, the legend or colour bar,
// all in one band across the top; drawn on any Canvas (the PNG's or a vector file's).
#include "runout/render/frame.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "runout/render/colormap.hpp"

namespace runout::render {

namespace {

// 1, 2, 5 times a power of ten, the largest not above `x`.
double nice_below(double x) {
  const double p = std::pow(10.0, std::floor(std::log10(x)));
  for (double m : {5.0, 2.0, 1.0})
    if (m * p <= x) return m * p;
  return p;
}

// Labels people read: whole numbers as such, the rest to three significant digits
// (d = 0.333 m, not 0.333333 m).
std::string format_number(double v) {
  char buf[32];
  if (std::abs(v - std::round(v)) < 1e-9) std::snprintf(buf, sizeof buf, "%.0f", v);
  else std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

}  // namespace

std::string FrameMaker::species_label(int s) const {
  const SpeciesDef& sp = scene_.species[s];
  char buf[160];
  if (sp.distribution != SizeDistribution::spread)
    std::snprintf(buf, sizeof buf, "%s, d = %.3g\u2013%.3g m", sp.name.c_str(), sp.min_diameter, sp.max_diameter);
  else
    std::snprintf(buf, sizeof buf, "%s, %s = %s m", sp.name.c_str(), s == setup_.largest_species ? "D" : "d",
                  format_number(sp.diameter).c_str());
  return buf;
}

std::vector<std::pair<Rgba, std::string>> FrameMaker::legend_entries() const {
  std::vector<std::pair<Rgba, std::string>> entries;
  if (options_.color == ColorMode::layer) {
    const bool many = std::count_if(setup_.counts.begin(), setup_.counts.end(), [](int c) { return c > 0; }) > 2;
    return {{palette::kSmall, "basal layer"}, {palette::kMutedSmall, "other small"},
            {palette::kMutedLarge, many ? "larger classes" : "large"}};
  }
  if (options_.color != ColorMode::species) return entries;
  for (std::size_t s = 0; s < scene_.species.size(); ++s)
    if (setup_.counts[s] > 0) entries.push_back({species_colour_[s], species_label(static_cast<int>(s))});
  return entries;
}

// Every overlay sits in one band across the top: the t* stamp and the scale bar at the left,
// the legend or colour bar at the right. The whole and deposit cameras fit the pile below the
// band, so no panel covers a disc (a strip frame has no empty corner to spare).
FrameMaker::OverlayLayout FrameMaker::overlay_layout() {
  OverlayLayout l;
  // From the width alone, so a frame whose height follows the camera can be sized with it;
  // the same as H / 36 in a 16:9 frame.
  l.fs = std::max(10, static_cast<int>(std::lround(options_.width / 64.0)));
  l.pad = std::max(4, l.fs / 2);
  l.line = std::max(1, l.fs / 9);
  l.asc = text_.ascent(l.fs);
  if (!options_.overlays) return l;
  const int stamp_bottom = l.pad + l.asc + l.fs / 3;
  const int scale_bottom = l.pad / 2 + l.asc + l.fs / 2 + 2 * l.line + l.pad / 2;
  int right_bottom;
  if (options_.color == ColorMode::spin || options_.color == ColorMode::speed)
    right_bottom = l.pad + l.asc + l.fs / 3 + std::max(6, l.fs * 2 / 3) + l.asc + 2 + l.fs / 3;
  else
    right_bottom = l.pad + (l.fs + l.fs / 3) * static_cast<int>(legend_entries().size());
  l.band = std::max({stamp_bottom, scale_bottom, right_bottom}) + l.pad / 2;
  return l;
}

void FrameMaker::draw_overlays(Canvas& canvas, const FramePlan& plan) {
  const double t_star = plan.t_star;
  const int W = options_.width;
  const OverlayLayout l = overlay_layout();
  const int fs = l.fs, pad = l.pad, line = l.line, asc = l.asc;
  const Rgba ink = palette::kInk, panel{255, 255, 255, 210};

  // t* stamp, top left; its panel as wide as the widest stamp, so the scale bar beside it
  // does not move from frame to frame.
  char stamp[64];
  std::snprintf(stamp, sizeof stamp, "t* = %.1f", t_star);
  const int stamp_w = std::max(text_.width(stamp, fs), text_.width("t* = 000.0", fs));
  canvas.rect(pad / 2, pad / 2, pad + stamp_w + pad / 2, pad + asc + fs / 3, panel);
  canvas.text(pad, pad + asc, stamp, fs, ink);

  // Scale bar in units of D, right of the stamp: about an eighth of the width.
  const double D = setup_.large_diameter;
  const double px_per_D = D * plan.view.scale;
  const double n_D = nice_below(std::max(W / 8.0 / px_per_D, 1e-3));
  const int bar = static_cast<int>(std::lround(n_D * px_per_D));
  const std::string label = format_number(n_D) + " D";
  const int bx = pad + stamp_w + 2 * pad, by = pad / 2 + asc + fs / 2 + line;
  canvas.rect(bx - pad / 2, pad / 2, bx + std::max(bar, text_.width(label, fs)) + pad / 2, by + line + pad / 2, panel);
  canvas.rect(bx, by, bx + bar, by + line + 1, ink);
  canvas.rect(bx, by - fs / 3, bx + line + 1, by + line + 1, ink);
  canvas.rect(bx + bar - line - 1, by - fs / 3, bx + bar, by + line + 1, ink);
  canvas.text(bx, by - fs / 3 - line - 1, label, fs, ink);

  // Legend or colour bar, top right.
  if (options_.color == ColorMode::spin || options_.color == ColorMode::speed) {
    const bool spin = options_.color == ColorMode::spin;
    const int bw = std::max(60, W / 5), bh = std::max(6, fs * 2 / 3);
    const int x1 = W - pad, x0 = x1 - bw;
    const std::string title = spin ? "ω √(d/g)" : "|v| / √(g d)";
    const double lo = spin ? -options_.spin_limit : 0.0, hi = spin ? options_.spin_limit : speed_limit_;
    const int y_title = pad + asc, y_bar = y_title + fs / 3, y_labels = y_bar + bh + asc + 2;
    canvas.rect(x0 - pad / 2, pad / 2, W - pad / 2, y_labels + fs / 3, panel);
    canvas.text(x0 + (bw - text_.width(title, fs)) / 2, y_title, title, fs, ink);
    for (int x = 0; x < bw; ++x) {
      const double t = (x + 0.5) / bw;
      const Rgba c = spin ? diverging(2 * t - 1) : viridis(t);
      canvas.rect(x0 + x, y_bar, x0 + x + 1, y_bar + bh, c);
    }
    // End labels inside the bar's span; a true minus sign.
    const std::string l0 = (lo < 0 ? "\u2212" : "") + format_number(std::abs(lo)), l1 = format_number(hi);
    canvas.text(x0, y_labels, l0, fs, ink);
    canvas.text(x1 - text_.width(l1, fs), y_labels, l1, fs, ink);
    if (spin) canvas.text(x0 + bw / 2 - text_.width("0", fs) / 2, y_labels, "0", fs, ink);
  } else {
    const auto entries = legend_entries();
    int widest = 0;
    for (const auto& e : entries) widest = std::max(widest, text_.width(e.second, fs));
    const int row = fs + fs / 3, sw = fs;  // swatch size
    const int x0 = W - pad - widest - sw - pad / 2;
    canvas.rect(x0 - pad / 2, pad / 2, W - pad / 2, pad + row * static_cast<int>(entries.size()), panel);
    for (std::size_t k = 0; k < entries.size(); ++k) {
      const int y = pad + static_cast<int>(k) * row;
      // A small disc as the swatch.
      canvas.disc(x0 + sw / 2.0, y + sw / 2.0, sw * 0.42, entries[k].first);
      canvas.text(x0 + sw + pad / 2, y + asc - (asc - sw) / 2 - 1, entries[k].second, fs, ink);
    }
  }
}

}  // namespace runout::render

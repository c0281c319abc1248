#include "scenarios/report/plot/plot.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <numbers>
#include <stdexcept>
#include <string_view>

#include <cairo-svg.h>
#include <cairo.h>
#include <fmt/format.h>

#include "scenarios/report/plot/plot_style.hpp"

namespace masnet::scenarios::plot {
namespace detail {

void set_colour(cairo_t* cr, Rgb c, double alpha) {
  if (alpha >= 1.0)
    cairo_set_source_rgb(cr, c.r, c.g, c.b);
  else
    cairo_set_source_rgba(cr, c.r, c.g, c.b, alpha);
}

void apply_style(cairo_t* cr, const Style& s) {
  set_colour(cr, s.colour, s.alpha);
  cairo_set_line_width(cr, s.width_px);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  if (s.dashed) {
    const std::array<double, 2> dash{5.0, 3.5};
    cairo_set_dash(cr, dash.data(), 2, 0.0);
  } else {
    cairo_set_dash(cr, nullptr, 0, 0.0);
  }
}

std::string compact_number(double v) {
  const double a = std::abs(v);
  if (a >= 1e6) return fmt::format("{:.3g}M", v / 1e6);
  if (a >= 1e4) return fmt::format("{:.3g}k", v / 1e3);
  if (a == std::round(a)) return fmt::format("{:.0f}", v);
  return fmt::format("{:.3g}", v);
}

}  // namespace detail

namespace {

using namespace detail;

// Decimals needed to print multiples of `step` exactly (0.25 → 2, 5 → 0).
int decimals_for(double step) {
  step = std::abs(step);
  if (!(step > 0) || !std::isfinite(step)) return 0;
  int d = 0;
  for (double scaled = step; d < 8 && std::abs(scaled - std::round(scaled)) > 1e-6 * scaled;
       scaled *= 10)
    ++d;
  return d;
}

}  // namespace

using namespace detail;

Rgb sequential(double u) {
  // ColorBrewer YlOrRd, 9 classes, interpolated in sRGB.
  static constexpr std::array<std::array<int, 3>, 9> kStops{{{255, 255, 204},
                                                             {255, 237, 160},
                                                             {254, 217, 118},
                                                             {254, 178, 76},
                                                             {253, 141, 60},
                                                             {252, 78, 42},
                                                             {227, 26, 28},
                                                             {189, 0, 38},
                                                             {128, 0, 38}}};
  if (!std::isfinite(u)) u = 0;
  u = std::clamp(u, 0.0, 1.0) * static_cast<double>(kStops.size() - 1);
  const std::size_t i = std::min(static_cast<std::size_t>(u), kStops.size() - 2);
  const double f = u - static_cast<double>(i);
  auto mix = [&](std::size_t c) { return ((1 - f) * kStops[i][c] + f * kStops[i + 1][c]) / 255.0; };
  return {mix(0), mix(1), mix(2)};
}

Rgb categorical(std::size_t i) {
  static constexpr std::array<std::array<int, 3>, 10> kTableau{{{31, 119, 180},
                                                                {255, 127, 14},
                                                                {44, 160, 44},
                                                                {214, 39, 40},
                                                                {148, 103, 189},
                                                                {140, 86, 75},
                                                                {227, 119, 194},
                                                                {127, 127, 127},
                                                                {188, 189, 34},
                                                                {23, 190, 207}}};
  const auto& c = kTableau[i % kTableau.size()];
  return {c[0] / 255.0, c[1] / 255.0, c[2] / 255.0};
}

double ColourScale::unit(double v) const {
  if (!std::isfinite(v)) return 0.0;
  if (scale == Scale::log) {
    if (v <= 0 || lo <= 0 || hi <= lo) return 0.0;
    return std::clamp((std::log10(v) - std::log10(lo)) / (std::log10(hi) - std::log10(lo)), 0.0,
                      1.0);
  }
  if (hi <= lo) return 0.0;
  return std::clamp((v - lo) / (hi - lo), 0.0, 1.0);
}

std::vector<double> nice_ticks(double lo, double hi, int target) {
  std::vector<double> ticks;
  if (!(hi > lo) || !std::isfinite(lo) || !std::isfinite(hi)) return ticks;
  const double raw = (hi - lo) / std::max(1, target);
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  double step = magnitude;
  for (double m : {1.0, 2.0, 5.0, 10.0}) {
    step = m * magnitude;
    if (step >= raw) break;
  }
  const double eps = step * 1e-9;
  for (double k = std::ceil((lo - eps) / step); k * step <= hi + eps; k += 1.0) {
    const double v = k * step;
    ticks.push_back(std::abs(v) < eps ? 0.0 : v);
  }
  return ticks;
}

std::vector<double> log_ticks(double lo, double hi) {
  std::vector<double> ticks;
  if (!(lo > 0) || !(hi > lo)) return ticks;
  const int first = static_cast<int>(std::floor(std::log10(lo))),
            last = static_cast<int>(std::ceil(std::log10(hi)));
  const bool dense = std::log10(hi / lo) < 2.5;
  for (int e = first; e <= last; ++e) {
    const double decade = std::pow(10.0, e);
    for (double m : dense ? std::vector<double>{1, 2, 5} : std::vector<double>{1}) {
      const double v = m * decade;
      if (v >= lo * (1 - 1e-9) && v <= hi * (1 + 1e-9)) ticks.push_back(v);
    }
  }
  return ticks;
}

std::string tick_label(double value, double step) {
  if (std::abs(value) <= std::abs(step) * 1e-9) return "0";
  const double a = std::max(std::abs(value), std::abs(step));
  if (a >= 1e4) {
    const double scale = a >= 1e6 ? 1e6 : 1e3;
    return fmt::format("{:.{}f}{}", value / scale, decimals_for(step / scale),
                       scale == 1e6 ? "M" : "k");
  }
  if (a < 1e-3) {
    const int e = static_cast<int>(std::floor(std::log10(std::abs(value))));
    const double m = value / std::pow(10.0, e);
    return fmt::format(
        "{}e{}",
        std::abs(m - std::round(m)) < 1e-6 ? fmt::format("{:.0f}", m) : fmt::format("{:.1f}", m),
        e);
  }
  return fmt::format("{:.{}f}", value, decimals_for(step));
}

void text(cairo_t* cr, double x, double y, const std::string& s, double size_px, Align h, Align v,
          bool bold, double angle_rad) {
  cairo_save(cr);
  cairo_select_font_face(cr, kFont, CAIRO_FONT_SLANT_NORMAL,
                         bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, size_px);
  cairo_text_extents_t ext;
  cairo_text_extents(cr, s.c_str(), &ext);
  const double dx = h == Align::start    ? 0.0
                    : h == Align::centre ? -ext.x_advance / 2
                                         : -ext.x_advance;
  // Vertical anchors from the font size, not the string, so that labels of a row line up.
  const double dy = v == Align::start ? 0.75 * size_px : v == Align::centre ? 0.36 * size_px : 0.0;
  cairo_translate(cr, x, y);
  if (angle_rad != 0.0) cairo_rotate(cr, angle_rad);
  cairo_move_to(cr, dx, dy);
  cairo_show_text(cr, s.c_str());
  cairo_restore(cr);
}

std::pair<double, double> data_range(const std::vector<const std::vector<double>*>& series,
                                     double pad, bool log) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const auto* s : series)
    for (double v : *s) {
      if (!std::isfinite(v) || (log && v <= 0)) continue;
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  if (!(lo <= hi)) return log ? std::pair{0.1, 10.0} : std::pair{0.0, 1.0};
  if (log) {
    if (hi <= lo) return {lo / 10, hi * 10};
    const double f = std::pow(hi / lo, pad);
    return {lo / f, hi * f};
  }
  if (hi <= lo) {
    const double d = lo == 0 ? 1.0 : std::abs(lo) * 0.1;
    return {lo - d, hi + d};
  }
  const double d = (hi - lo) * pad;
  return {lo - d, hi + d};
}

void colour_bar(cairo_t* cr, Box box, const ColourScale& colours, const std::string& label) {
  cairo_save(cr);
  // A 1 × 256 image of the colour map, stretched over the box (top = hi).
  constexpr int kSteps = 256;
  cairo_surface_t* image = cairo_image_surface_create(CAIRO_FORMAT_RGB24, 1, kSteps);
  cairo_surface_flush(image);
  unsigned char* data = cairo_image_surface_get_data(image);
  const int stride = cairo_image_surface_get_stride(image);
  for (int i = 0; i < kSteps; ++i) {
    const Rgb c = sequential(1.0 - (i + 0.5) / kSteps);
    auto byte = [](double u) {
      return static_cast<std::uint32_t>(std::lround(std::clamp(u, 0.0, 1.0) * 255));
    };
    *reinterpret_cast<std::uint32_t*>(data + static_cast<std::ptrdiff_t>(i) * stride) =
        byte(c.r) << 16 | byte(c.g) << 8 | byte(c.b);
  }
  cairo_surface_mark_dirty(image);
  cairo_save(cr);
  cairo_translate(cr, box.x, box.y);
  cairo_scale(cr, box.w, box.h / kSteps);
  cairo_set_source_surface(cr, image, 0, 0);
  cairo_pattern_set_filter(cairo_get_source(cr), CAIRO_FILTER_NEAREST);
  cairo_paint(cr);
  cairo_restore(cr);
  cairo_surface_destroy(image);

  set_colour(cr, kBlack);
  cairo_set_line_width(cr, 1.0);
  cairo_rectangle(cr, box.x, box.y, box.w, box.h);
  cairo_stroke(cr);
  const bool log = colours.scale == Scale::log;
  const std::vector<double> ticks =
      log ? log_ticks(colours.lo, colours.hi) : nice_ticks(colours.lo, colours.hi, 6);
  const double step = ticks.size() > 1 ? ticks[1] - ticks[0] : 1.0;
  double widest = 0;
  for (double v : ticks) {
    const double y = box.y + box.h * (1.0 - colours.unit(v));
    cairo_move_to(cr, box.x + box.w, y);
    cairo_line_to(cr, box.x + box.w + 4, y);
    cairo_stroke(cr);
    const std::string s = tick_label(v, log ? v : step);
    set_colour(cr, kTickText);
    text(cr, box.x + box.w + 7, y, s, 10, Align::start, Align::centre);
    set_colour(cr, kBlack);
    widest = std::max(widest, static_cast<double>(s.size()) * 6.2);
  }
  text(cr, box.x + box.w + 14 + widest, box.y + box.h / 2, label, 12, Align::centre, Align::start,
       false, -std::numbers::pi / 2);
  cairo_restore(cr);
}

}  // namespace masnet::scenarios::plot

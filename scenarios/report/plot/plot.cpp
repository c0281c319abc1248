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

namespace masnet::scenarios::plot {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr const char* kFont = "DejaVu Sans";
constexpr Rgb kBlack{0, 0, 0};
constexpr Rgb kGrid{0.88, 0.88, 0.88};
constexpr Rgb kTickText{0.15, 0.15, 0.15};

void set_colour(cairo_t* cr, Rgb c, double alpha = 1.0) {
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

std::string compact_number(double v) {
  const double a = std::abs(v);
  if (a >= 1e6) return fmt::format("{:.3g}M", v / 1e6);
  if (a >= 1e4) return fmt::format("{:.3g}k", v / 1e3);
  if (a == std::round(a)) return fmt::format("{:.0f}", v);
  return fmt::format("{:.3g}", v);
}

}  // namespace

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

// ---------------------------------------------------------------------------------------------
// Axes

Axes::Axes(cairo_t* cr, Box frame) : cr_(cr), frame_(frame) {}

Axes& Axes::x_range(double lo, double hi, Scale scale) {
  x_lo_ = lo;
  x_hi_ = hi;
  x_scale_ = scale;
  return *this;
}

Axes& Axes::y_range(double lo, double hi, Scale scale) {
  y_lo_ = lo;
  y_hi_ = hi;
  y_scale_ = scale;
  return *this;
}

Axes& Axes::equal_aspect() {
  const double sx = frame_.w / (x_hi_ - x_lo_), sy = frame_.h / (y_hi_ - y_lo_);
  const double s = std::min(sx, sy);
  const double w = s * (x_hi_ - x_lo_), h = s * (y_hi_ - y_lo_);
  frame_ = {frame_.x + (frame_.w - w) / 2, frame_.y + (frame_.h - h) / 2, w, h};
  return *this;
}

double Axes::map_x(double x) const {
  if (x_scale_ == Scale::log) {
    if (!(x > 0)) return kNaN;
    return (std::log10(x) - std::log10(x_lo_)) / (std::log10(x_hi_) - std::log10(x_lo_));
  }
  return (x - x_lo_) / (x_hi_ - x_lo_);
}

double Axes::map_y(double y) const {
  if (y_scale_ == Scale::log) {
    if (!(y > 0)) return kNaN;
    return (std::log10(y) - std::log10(y_lo_)) / (std::log10(y_hi_) - std::log10(y_lo_));
  }
  return (y - y_lo_) / (y_hi_ - y_lo_);
}

double Axes::px(double x) const {
  return frame_.x + map_x(x) * frame_.w;
}
double Axes::py(double y) const {
  return frame_.y + frame_.h - map_y(y) * frame_.h;
}

void Axes::decorate(const std::string& x_label, const std::string& y_label) {
  const double tick_px = 4, font_px = 11;
  std::vector<double> xt, yt;
  double x_step = 1, y_step = 1;
  if (categories_.empty()) {
    xt = x_scale_ == Scale::log ? log_ticks(x_lo_, x_hi_) : nice_ticks(x_lo_, x_hi_, 7);
    if (xt.size() > 1 && x_scale_ == Scale::linear) x_step = xt[1] - xt[0];
  }
  yt = y_scale_ == Scale::log ? log_ticks(y_lo_, y_hi_) : nice_ticks(y_lo_, y_hi_, 6);
  if (yt.size() > 1 && y_scale_ == Scale::linear) y_step = yt[1] - yt[0];

  cairo_save(cr_);
  cairo_set_dash(cr_, nullptr, 0, 0.0);
  cairo_set_line_width(cr_, 1.0);
  set_colour(cr_, kGrid);
  for (double v : xt) {
    const double x = std::round(px(v)) + 0.5;
    cairo_move_to(cr_, x, frame_.y);
    cairo_line_to(cr_, x, frame_.y + frame_.h);
  }
  for (double v : yt) {
    const double y = std::round(py(v)) + 0.5;
    cairo_move_to(cr_, frame_.x, y);
    cairo_line_to(cr_, frame_.x + frame_.w, y);
  }
  cairo_stroke(cr_);

  set_colour(cr_, kBlack);
  cairo_rectangle(cr_, frame_.x, frame_.y, frame_.w, frame_.h);
  cairo_stroke(cr_);
  for (double v : xt) {
    const double x = std::round(px(v)) + 0.5;
    cairo_move_to(cr_, x, frame_.y + frame_.h);
    cairo_line_to(cr_, x, frame_.y + frame_.h + tick_px);
  }
  for (double v : yt) {
    const double y = std::round(py(v)) + 0.5;
    cairo_move_to(cr_, frame_.x, y);
    cairo_line_to(cr_, frame_.x - tick_px, y);
  }
  cairo_stroke(cr_);

  set_colour(cr_, kTickText);
  for (double v : xt)
    text(cr_, px(v), frame_.y + frame_.h + tick_px + 3,
         tick_label(v, x_scale_ == Scale::log ? v : x_step), font_px, Align::centre, Align::start);
  // Category names: level when they fit their slot, else slanted and anchored at their end.
  double x_label_offset = tick_px + 20;
  if (!categories_.empty()) {
    cairo_select_font_face(cr_, kFont, CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr_, font_px - 1);
    double longest = 0;
    for (const std::string& c : categories_) {
      cairo_text_extents_t ext;
      cairo_text_extents(cr_, c.c_str(), &ext);
      longest = std::max(longest, ext.x_advance);
    }
    const double slot = std::abs(px(1.0) - px(0.0));
    const bool slanted = longest > 0.95 * slot;
    const double angle = -std::numbers::pi / 5;
    for (std::size_t i = 0; i < categories_.size(); ++i) {
      const double x = px(static_cast<double>(i)), y = frame_.y + frame_.h + tick_px + 3;
      if (slanted)
        text(cr_, x + 3, y + 2, categories_[i], font_px - 1, Align::end, Align::centre, false,
             angle);
      else
        text(cr_, x, y, categories_[i], font_px - 1, Align::centre, Align::start);
    }
    if (slanted) x_label_offset = tick_px + 10 + longest * std::sin(-angle);
  }
  double widest = 0;
  for (double v : yt) {
    const std::string s = tick_label(v, y_scale_ == Scale::log ? v : y_step);
    text(cr_, frame_.x - tick_px - 3, py(v), s, font_px, Align::end, Align::centre);
    widest = std::max(widest, static_cast<double>(s.size()) * font_px * 0.62);
  }
  set_colour(cr_, kBlack);
  if (!x_label.empty())
    text(cr_, frame_.x + frame_.w / 2, frame_.y + frame_.h + x_label_offset, x_label, 12,
         Align::centre, Align::start);
  if (!y_label.empty())
    text(cr_, frame_.x - tick_px - 10 - widest, frame_.y + frame_.h / 2, y_label, 12, Align::centre,
         Align::end, false, -std::numbers::pi / 2);
  cairo_restore(cr_);
}

void Axes::title(const std::string& s) {
  cairo_save(cr_);
  set_colour(cr_, kBlack);
  text(cr_, frame_.x + frame_.w / 2, frame_.y - 10, s, 14, Align::centre, Align::end, true);
  cairo_restore(cr_);
}

void Axes::clip() {
  cairo_save(cr_);
  cairo_rectangle(cr_, frame_.x, frame_.y, frame_.w, frame_.h);
  cairo_clip(cr_);
}

void Axes::unclip() {
  cairo_restore(cr_);
}

void Axes::line(const std::vector<double>& xs, const std::vector<double>& ys, const Style& style,
                const std::string& label) {
  cairo_save(cr_);
  apply_style(cr_, style);
  bool pen_down = false;
  const std::size_t n = std::min(xs.size(), ys.size());
  for (std::size_t i = 0; i < n; ++i) {
    const double x = px(xs[i]), y = py(ys[i]);
    if (!std::isfinite(x) || !std::isfinite(y)) {
      pen_down = false;
      continue;
    }
    if (pen_down)
      cairo_line_to(cr_, x, y);
    else
      cairo_move_to(cr_, x, y);
    pen_down = true;
  }
  cairo_stroke(cr_);
  cairo_restore(cr_);
  if (!label.empty()) legend_.push_back({label, style, true, Marker::none, {}, {}, 0});
}

void Axes::steps(const std::vector<double>& xs, const std::vector<double>& ys, const Style& style,
                 const std::string& label) {
  std::vector<double> sx, sy;
  const std::size_t n = std::min(xs.size(), ys.size());
  for (std::size_t i = 0; i < n; ++i) {
    if (i > 0) {
      sx.push_back(xs[i]);
      sy.push_back(ys[i - 1]);
    }
    sx.push_back(xs[i]);
    sy.push_back(ys[i]);
  }
  line(sx, sy, style, label);
}

void Axes::polygon(const std::vector<Point>& points, const Style& style, bool closed) {
  if (points.size() < 2) return;
  cairo_save(cr_);
  apply_style(cr_, style);
  cairo_move_to(cr_, px(points[0].x), py(points[0].y));
  for (std::size_t i = 1; i < points.size(); ++i)
    cairo_line_to(cr_, px(points[i].x), py(points[i].y));
  if (closed) cairo_close_path(cr_);
  cairo_stroke(cr_);
  cairo_restore(cr_);
}

void Axes::filled_polygon(const std::vector<Point>& points, Rgb fill, double alpha) {
  if (points.size() < 3) return;
  cairo_save(cr_);
  set_colour(cr_, fill, alpha);
  cairo_move_to(cr_, px(points[0].x), py(points[0].y));
  for (std::size_t i = 1; i < points.size(); ++i)
    cairo_line_to(cr_, px(points[i].x), py(points[i].y));
  cairo_close_path(cr_);
  cairo_fill(cr_);
  cairo_restore(cr_);
}

void Axes::draw_marker(double x, double y, Marker marker, double size_px, Rgb fill,
                       Rgb edge) const {
  if (!std::isfinite(x) || !std::isfinite(y) || marker == Marker::none) return;
  const double r = size_px / 2;
  cairo_save(cr_);
  cairo_set_dash(cr_, nullptr, 0, 0.0);
  cairo_new_path(cr_);
  switch (marker) {
    case Marker::dot:
      cairo_arc(cr_, x, y, r, 0, 2 * std::numbers::pi);
      break;
    case Marker::diamond:
      cairo_move_to(cr_, x, y - r * 1.3);
      cairo_line_to(cr_, x + r, y);
      cairo_line_to(cr_, x, y + r * 1.3);
      cairo_line_to(cr_, x - r, y);
      cairo_close_path(cr_);
      break;
    case Marker::square:
      cairo_rectangle(cr_, x - r, y - r, 2 * r, 2 * r);
      break;
    case Marker::cross:
      cairo_move_to(cr_, x - r, y - r);
      cairo_line_to(cr_, x + r, y + r);
      cairo_move_to(cr_, x - r, y + r);
      cairo_line_to(cr_, x + r, y - r);
      set_colour(cr_, edge);
      cairo_set_line_width(cr_, std::max(1.5, size_px / 5));
      cairo_set_line_cap(cr_, CAIRO_LINE_CAP_ROUND);
      cairo_stroke(cr_);
      cairo_restore(cr_);
      return;
    case Marker::none:
      break;
  }
  set_colour(cr_, fill);
  cairo_fill_preserve(cr_);
  set_colour(cr_, edge);
  cairo_set_line_width(cr_, 1.2);
  cairo_stroke(cr_);
  cairo_restore(cr_);
}

void Axes::markers(const std::vector<Point>& points, Marker marker, double size_px, Rgb fill,
                   Rgb edge, const std::string& label) {
  for (const Point& p : points)
    draw_marker(px(p.x), py(p.y), marker, size_px, fill, edge);
  if (!label.empty())
    legend_.push_back({label, Style{edge, 1.2}, false, marker, fill, edge, size_px});
}

void Axes::circle(Point centre, double r, const Style& style) {
  const double r_px = r / (x_hi_ - x_lo_) * frame_.w;
  if (!(r_px > 0)) return;
  cairo_save(cr_);
  apply_style(cr_, style);
  cairo_new_path(cr_);
  cairo_arc(cr_, px(centre.x), py(centre.y), r_px, 0, 2 * std::numbers::pi);
  cairo_stroke(cr_);
  cairo_restore(cr_);
}

void Axes::arrow(Point from, Point to, const Style& style, double head_px) {
  const double x0 = px(from.x), y0 = py(from.y), x1 = px(to.x), y1 = py(to.y);
  const double len = std::hypot(x1 - x0, y1 - y0);
  if (!(len > 1e-9)) return;
  const double ux = (x1 - x0) / len, uy = (y1 - y0) / len;
  cairo_save(cr_);
  apply_style(cr_, style);
  cairo_move_to(cr_, x0, y0);
  // Stop the shaft inside the head so that a thick line does not poke through its tip.
  const double shaft = std::max(0.0, len - head_px * 0.6);
  cairo_line_to(cr_, x0 + ux * shaft, y0 + uy * shaft);
  cairo_stroke(cr_);
  cairo_set_dash(cr_, nullptr, 0, 0.0);
  cairo_move_to(cr_, x1, y1);
  cairo_line_to(cr_, x1 - ux * head_px - uy * head_px * 0.45,
                y1 - uy * head_px + ux * head_px * 0.45);
  cairo_line_to(cr_, x1 - ux * head_px + uy * head_px * 0.45,
                y1 - uy * head_px - ux * head_px * 0.45);
  cairo_close_path(cr_);
  cairo_fill(cr_);
  cairo_restore(cr_);
}

void Axes::bars(const std::vector<double>& values, Rgb fill, const std::string& label) {
  cairo_save(cr_);
  const double base = y_scale_ == Scale::log ? y_lo_ : std::max(y_lo_, 0.0);
  for (std::size_t i = 0; i < values.size(); ++i) {
    const double x = static_cast<double>(i), v = values[i];
    const double left = px(x - 0.35), right = px(x + 0.35), bottom = py(base);
    double top = bottom;
    if (std::isfinite(v) && (y_scale_ == Scale::linear || v > 0)) {
      top = py(v);
      set_colour(cr_, fill);
      cairo_rectangle(cr_, left, top, right - left, bottom - top);
      cairo_fill(cr_);
    }
    set_colour(cr_, kTickText);
    text(cr_, (left + right) / 2, top - 3, compact_number(std::isfinite(v) ? v : 0.0), 10,
         Align::centre, Align::end);
  }
  cairo_restore(cr_);
  if (!label.empty())
    legend_.push_back({label, Style{fill}, false, Marker::square, fill, fill, 10});
}

void Axes::histogram(const std::vector<double>& edges, const std::vector<double>& counts, Rgb fill,
                     double alpha, const std::string& label) {
  cairo_save(cr_);
  const double base = y_scale_ == Scale::log ? y_lo_ : 0.0;
  for (std::size_t i = 0; i + 1 < edges.size() && i < counts.size(); ++i) {
    if (!(counts[i] > 0)) continue;
    const double left = px(edges[i]), right = px(edges[i + 1]), top = py(counts[i]),
                 bottom = py(base);
    set_colour(cr_, fill, alpha);
    cairo_rectangle(cr_, left, top, right - left, bottom - top);
    cairo_fill_preserve(cr_);
    set_colour(cr_, {1, 1, 1}, 0.8);
    cairo_set_line_width(cr_, 0.6);
    cairo_stroke(cr_);
  }
  cairo_restore(cr_);
  if (!label.empty())
    legend_.push_back({label, Style{fill, 1, false, alpha}, false, Marker::square, fill, fill, 10});
}

void Axes::heat_map(const Raster& raster, const ColourScale& colours) {
  if (raster.nx == 0 || raster.ny == 0 || raster.values.size() != raster.nx * raster.ny) return;
  // Each cell becomes k × k pixels, so that a viewer that smooths the embedded image (SVG)
  // still shows crisp cells.
  const std::size_t k = std::clamp<std::size_t>(320 / std::max(raster.nx, raster.ny), 1, 16);
  const int w = static_cast<int>(raster.nx * k), h = static_cast<int>(raster.ny * k);
  cairo_surface_t* image = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, w, h);
  cairo_surface_flush(image);
  unsigned char* data = cairo_image_surface_get_data(image);
  const int stride = cairo_image_surface_get_stride(image);
  for (int row = 0; row < h; ++row) {
    auto* line = reinterpret_cast<std::uint32_t*>(data + static_cast<std::ptrdiff_t>(row) * stride);
    const std::size_t j = raster.ny - 1 - static_cast<std::size_t>(row) / k;  // image rows go down
    for (int col = 0; col < w; ++col) {
      const double v = raster.values[j * raster.nx + static_cast<std::size_t>(col) / k];
      if (!std::isfinite(v)) {
        line[col] = 0;
        continue;
      }
      const Rgb c = colours(v);
      auto byte = [](double u) {
        return static_cast<std::uint32_t>(std::lround(std::clamp(u, 0.0, 1.0) * 255));
      };
      line[col] = 0xFF000000u | byte(c.r) << 16 | byte(c.g) << 8 | byte(c.b);
    }
  }
  cairo_surface_mark_dirty(image);
  cairo_save(cr_);
  const double left = px(raster.x0), right = px(raster.x1), top = py(raster.y1),
               bottom = py(raster.y0);
  cairo_translate(cr_, left, top);
  cairo_scale(cr_, (right - left) / w, (bottom - top) / h);
  cairo_set_source_surface(cr_, image, 0, 0);
  cairo_pattern_set_filter(cairo_get_source(cr_), CAIRO_FILTER_NEAREST);
  cairo_paint(cr_);
  cairo_restore(cr_);
  cairo_surface_destroy(image);
}

void Axes::add_legend_entry(const std::string& label, const Style& style, Marker marker, Rgb fill,
                            double marker_px) {
  legend_.push_back({label, style, marker == Marker::none || style.dashed, marker, fill,
                     style.colour, marker_px});
}

void Axes::draw_entry_sample(const Entry& e, double x, double y) const {
  if (e.has_line) {
    cairo_save(cr_);
    apply_style(cr_, e.style);
    cairo_move_to(cr_, x, y);
    cairo_line_to(cr_, x + 22, y);
    cairo_stroke(cr_);
    cairo_restore(cr_);
  }
  if (e.marker != Marker::none)
    draw_marker(x + 11, y, e.marker, e.marker_px > 0 ? e.marker_px : 8, e.fill, e.edge);
}

void Axes::legend(Placement where) {
  if (legend_.empty()) return;
  const double font_px = 11, row_px = 16, sample_px = 28, pad = 6;
  cairo_save(cr_);
  cairo_select_font_face(cr_, kFont, CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr_, font_px);
  std::vector<double> widths;
  double widest = 0;
  for (const Entry& e : legend_) {
    cairo_text_extents_t ext;
    cairo_text_extents(cr_, e.label.c_str(), &ext);
    widths.push_back(ext.x_advance);
    widest = std::max(widest, ext.x_advance);
  }
  if (where == Placement::below) {
    // Centred rows under the x-axis label, wrapped at about the frame's width.
    const double max_row = frame_.w + 100;
    std::vector<std::pair<std::size_t, std::size_t>> rows;  // [first, last) entries
    std::vector<double> row_widths;
    for (std::size_t i = 0; i < legend_.size(); ++i) {
      const double w = sample_px + widths[i] + 14;
      if (rows.empty() || row_widths.back() + w > max_row) {
        rows.emplace_back(i, i);
        row_widths.push_back(0);
      }
      rows.back().second = i + 1;
      row_widths.back() += w;
    }
    for (std::size_t r = 0; r < rows.size(); ++r) {
      double x = frame_.x + (frame_.w - row_widths[r]) / 2;
      const double y = frame_.y + frame_.h + 48 + 18 * static_cast<double>(r);
      for (std::size_t i = rows[r].first; i < rows[r].second; ++i) {
        draw_entry_sample(legend_[i], x, y);
        set_colour(cr_, kBlack);
        text(cr_, x + sample_px, y, legend_[i].label, font_px, Align::start, Align::centre);
        x += sample_px + widths[i] + 14;
      }
    }
    cairo_restore(cr_);
    return;
  }
  const double w = pad * 2 + sample_px + widest,
               h = pad * 2 + row_px * static_cast<double>(legend_.size());
  const bool right = where == Placement::top_right || where == Placement::bottom_right;
  const bool top = where == Placement::top_left || where == Placement::top_right;
  const double x = right ? frame_.x + frame_.w - w - 8 : frame_.x + 8;
  const double y = top ? frame_.y + 8 : frame_.y + frame_.h - h - 8;
  set_colour(cr_, {1, 1, 1}, 0.88);
  cairo_rectangle(cr_, x, y, w, h);
  cairo_fill_preserve(cr_);
  set_colour(cr_, {0.6, 0.6, 0.6});
  cairo_set_line_width(cr_, 0.8);
  cairo_stroke(cr_);
  for (std::size_t i = 0; i < legend_.size(); ++i) {
    const double cy = y + pad + row_px * (static_cast<double>(i) + 0.5);
    draw_entry_sample(legend_[i], x + pad, cy);
    set_colour(cr_, kBlack);
    text(cr_, x + pad + sample_px, cy, legend_[i].label, font_px, Align::start, Align::centre);
  }
  cairo_restore(cr_);
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

// ---------------------------------------------------------------------------------------------
// Files

namespace {

cairo_status_t append_to_string(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

void check(cairo_status_t status, const std::filesystem::path& path) {
  if (status != CAIRO_STATUS_SUCCESS)
    throw std::runtime_error(
        fmt::format("cannot draw '{}': {}", path.string(), cairo_status_to_string(status)));
}

// The percentages of `stroke:rgb(r%,g%,b%)` in a Cairo style attribute, if present.
bool stroke_colour(std::string_view element, Rgb& out) {
  const std::size_t at = element.find("stroke:rgb(");
  if (at == std::string_view::npos) return false;
  std::array<double, 3> c{};
  std::size_t pos = at + 11;
  for (double& v : c) {
    const std::size_t end = element.find_first_of("%,)", pos);
    if (end == std::string_view::npos) return false;
    try {
      v = std::stod(std::string(element.substr(pos, end - pos))) / 100.0;
    } catch (const std::exception&) {
      return false;
    }
    pos = element.find_first_not_of("%,", end);
    if (pos == std::string_view::npos) return false;
  }
  out = {c[0], c[1], c[2]};
  return true;
}

}  // namespace

std::string finish_svg(std::string svg, const std::vector<SvgClass>& classes) {
  // 1. Cairo numbers some ids (image, surface, source) from process-wide counters: renumber
  //    them in order of first appearance so that a re-render is byte-identical.
  std::string out;
  out.reserve(svg.size() + 64 * classes.size());
  std::map<std::string, std::map<std::string, int>> ids;
  static constexpr std::array<std::string_view, 6> kPrefixes{"image",   "surface", "source",
                                                             "pattern", "mask",    "clip"};
  for (std::size_t i = 0; i < svg.size();) {
    bool replaced = false;
    if (i > 0 && (svg[i - 1] == '"' || svg[i - 1] == '#')) {
      for (std::string_view prefix : kPrefixes) {
        if (svg.compare(i, prefix.size(), prefix) != 0) continue;
        std::size_t end = i + prefix.size();
        while (end < svg.size() && std::isdigit(static_cast<unsigned char>(svg[end])))
          ++end;
        if (end == i + prefix.size()) continue;
        auto& seen = ids[std::string(prefix)];
        const auto [it, fresh] =
            seen.try_emplace(svg.substr(i + prefix.size(), end - i - prefix.size()),
                             static_cast<int>(seen.size()) + 1);
        (void)fresh;
        out += prefix;
        out += std::to_string(it->second);
        i = end;
        replaced = true;
        break;
      }
    }
    if (!replaced) out += svg[i++];
  }
  // 2. Tag the paths whose stroke colour is reserved for a class.
  if (classes.empty()) return out;
  std::string tagged;
  tagged.reserve(out.size() + 64);
  std::vector<int> counts(classes.size(), 0);
  std::size_t pos = 0;
  for (;;) {
    const std::size_t at = out.find("<path ", pos);
    if (at == std::string::npos) break;
    const std::size_t end = out.find('>', at);
    tagged.append(out, pos, at + 5 - pos);
    Rgb c;
    if (end != std::string::npos && stroke_colour(std::string_view(out).substr(at, end - at), c)) {
      for (std::size_t k = 0; k < classes.size(); ++k) {
        const Rgb& s = classes[k].stroke;
        if (std::abs(c.r - s.r) < 6e-4 && std::abs(c.g - s.g) < 6e-4 &&
            std::abs(c.b - s.b) < 6e-4) {
          tagged += fmt::format(" class=\"{0}\" id=\"{0}-{1}\"", classes[k].name, counts[k]++);
          break;
        }
      }
    }
    pos = at + 5;
  }
  tagged.append(out, pos, std::string::npos);
  return tagged;
}

void write_figure(const FileWriter& write, const std::filesystem::path& stem, double width,
                  double height, const std::function<void(cairo_t*)>& draw,
                  const std::vector<SvgClass>& classes, double png_scale) {
  auto paint = [&](cairo_t* cr) {
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    draw(cr);
  };
  const std::filesystem::path svg_path = std::filesystem::path(stem).concat(".svg");
  const std::filesystem::path png_path = std::filesystem::path(stem).concat(".png");
  {
    std::string svg;
    cairo_surface_t* surface =
        cairo_svg_surface_create_for_stream(append_to_string, &svg, width, height);
    cairo_svg_surface_set_document_unit(surface, CAIRO_SVG_UNIT_PX);
    cairo_t* cr = cairo_create(surface);
    paint(cr);
    const cairo_status_t drawn = cairo_status(cr);
    cairo_destroy(cr);
    cairo_surface_finish(surface);
    const cairo_status_t finished = cairo_surface_status(surface);
    cairo_surface_destroy(surface);
    check(drawn, svg_path);
    check(finished, svg_path);
    write(svg_path, finish_svg(std::move(svg), classes));
  }
  {
    const int w = static_cast<int>(std::lround(width * png_scale)),
              h = static_cast<int>(std::lround(height * png_scale));
    cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, w, h);
    cairo_t* cr = cairo_create(surface);
    cairo_scale(cr, png_scale, png_scale);
    paint(cr);
    const cairo_status_t drawn = cairo_status(cr);
    cairo_destroy(cr);
    // Encoded in memory and stored by `write`, whose errors name the system's reason
    // (Cairo's own file writer says only "error while writing to output stream").
    std::string png;
    const cairo_status_t encoded =
        drawn == CAIRO_STATUS_SUCCESS
            ? cairo_surface_write_to_png_stream(surface, append_to_string, &png)
            : drawn;
    cairo_surface_destroy(surface);
    check(encoded, png_path);
    write(png_path, png);
  }
}

}  // namespace masnet::scenarios::plot

// Axes: data coordinates mapped onto a box of the figure, with ticks, labels, series, markers,
// heat maps and a legend.
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <stdexcept>

#include <cairo.h>
#include <fmt/format.h>

#include "scenarios/report/plot/plot.hpp"
#include "scenarios/report/plot/plot_style.hpp"

namespace masnet::scenarios::plot {
using namespace detail;

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

}  // namespace masnet::scenarios::plot

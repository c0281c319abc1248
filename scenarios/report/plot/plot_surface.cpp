// A height field as a 3-D surface: the projection, the quads in painter's order, and the box's
// panes and axes around them.
#include "scenarios/report/plot/plot_surface.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>

#include <cairo.h>

#include "scenarios/report/plot/plot_style.hpp"

namespace masnet::scenarios::plot {
using namespace detail;

namespace {

double dot(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

double span_or_one(double lo, double hi) {
  return hi > lo ? hi - lo : 1.0;
}

constexpr Rgb kPane{0.965, 0.965, 0.965};
constexpr Rgb kPaneEdge{0.6, 0.6, 0.6};
constexpr Rgb kQuadEdge{0.2, 0.2, 0.2};

}  // namespace

SurfaceProjection::SurfaceProjection(Box frame, Point3 lo, Point3 hi, View view, double z_aspect)
    : lo_(lo), hi_(hi) {
  const double sx = span_or_one(lo.x, hi.x), sy = span_or_one(lo.y, hi.y);
  const double longer = std::max(sx, sy);
  extent_ = {sx / longer, sy / longer, z_aspect > 0 ? z_aspect : 0.6};
  const double a = view.azimuth_rad, e = view.elevation_rad;
  right_ = {std::cos(a), std::sin(a), 0.0};
  up_ = {-std::sin(e) * std::sin(a), std::sin(e) * std::cos(a), std::cos(e)};
  toward_viewer_ = {std::cos(e) * std::sin(a), -std::cos(e) * std::cos(a), std::sin(e)};
  double x_lo = std::numeric_limits<double>::infinity(), x_hi = -x_lo, y_lo = x_lo, y_hi = -x_lo;
  for (int k = 0; k < 8; ++k) {
    const auto c = centred({k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z});
    x_lo = std::min(x_lo, dot(c, right_));
    x_hi = std::max(x_hi, dot(c, right_));
    y_lo = std::min(y_lo, dot(c, up_));
    y_hi = std::max(y_hi, dot(c, up_));
  }
  const double w = x_hi - x_lo, h = y_hi - y_lo;
  scale_px_ = std::min(w > 0 ? frame.w / w : 1.0, h > 0 ? frame.h / h : 1.0);
  mid_right_ = (x_lo + x_hi) / 2;
  mid_up_ = (y_lo + y_hi) / 2;
  centre_x_ = frame.x + frame.w / 2;
  centre_y_ = frame.y + frame.h / 2;
}

std::array<double, 3> SurfaceProjection::centred(Point3 p) const {
  return {((p.x - lo_.x) / span_or_one(lo_.x, hi_.x) - 0.5) * extent_[0],
          ((p.y - lo_.y) / span_or_one(lo_.y, hi_.y) - 0.5) * extent_[1],
          ((p.z - lo_.z) / span_or_one(lo_.z, hi_.z) - 0.5) * extent_[2]};
}

Point SurfaceProjection::project(Point3 p) const {
  const auto c = centred(p);
  return {centre_x_ + scale_px_ * (dot(c, right_) - mid_right_),
          centre_y_ - scale_px_ * (dot(c, up_) - mid_up_)};
}

double SurfaceProjection::depth(Point3 p) const {
  return -dot(centred(p), toward_viewer_);
}

std::vector<SurfaceQuad> surface_quads(const Raster& raster, std::size_t max_side) {
  std::vector<SurfaceQuad> quads;
  if (raster.nx < 2 || raster.ny < 2 || raster.values.size() != raster.nx * raster.ny) return quads;
  // Every k-th cell along a side, the last one always kept.
  auto picked = [&](std::size_t n) {
    const std::size_t step =
        n <= max_side || max_side < 2 ? 1 : (n - 1 + max_side - 2) / (max_side - 1);
    std::vector<std::size_t> out;
    for (std::size_t i = 0; i < n; i += step)
      out.push_back(i);
    if (out.back() != n - 1) out.push_back(n - 1);
    return out;
  };
  const std::vector<std::size_t> is = picked(raster.nx), js = picked(raster.ny);
  const double hx = (raster.x1 - raster.x0) / static_cast<double>(raster.nx),
               hy = (raster.y1 - raster.y0) / static_cast<double>(raster.ny);
  auto node = [&](std::size_t i, std::size_t j) {
    return Point3{raster.x0 + (static_cast<double>(i) + 0.5) * hx,
                  raster.y0 + (static_cast<double>(j) + 0.5) * hy,
                  raster.values[j * raster.nx + i]};
  };
  for (std::size_t b = 0; b + 1 < js.size(); ++b)
    for (std::size_t a = 0; a + 1 < is.size(); ++a) {
      SurfaceQuad q{{node(is[a], js[b]), node(is[a + 1], js[b]), node(is[a + 1], js[b + 1]),
                     node(is[a], js[b + 1])}};
      double sum = 0;
      for (const Point3& c : q.corners)
        sum += c.z;
      if (!std::isfinite(sum)) continue;
      q.height = sum / 4;
      quads.push_back(q);
    }
  return quads;
}

std::vector<std::size_t> painter_order(const std::vector<SurfaceQuad>& quads,
                                       const SurfaceProjection& projection) {
  // Depth of each quad's centre on the floor: for a height field seen from above, of two
  // points on one line of sight the one nearer along the floor is the nearer one.
  std::vector<double> depth(quads.size());
  for (std::size_t k = 0; k < quads.size(); ++k) {
    Point3 centre{0, 0, projection.lo().z};
    for (const Point3& c : quads[k].corners) {
      centre.x += c.x / 4;
      centre.y += c.y / 4;
    }
    depth[k] = projection.depth(centre);
  }
  std::vector<std::size_t> order(quads.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return depth[a] > depth[b]; });
  return order;
}

namespace {

void move_line(cairo_t* cr, const SurfaceProjection& proj, Point3 a, Point3 b) {
  const Point p = proj.project(a), q = proj.project(b);
  cairo_move_to(cr, p.x, p.y);
  cairo_line_to(cr, q.x, q.y);
}

void pane(cairo_t* cr, const SurfaceProjection& proj, const std::array<Point3, 4>& corners) {
  for (std::size_t k = 0; k < corners.size(); ++k) {
    const Point p = proj.project(corners[k]);
    if (k == 0)
      cairo_move_to(cr, p.x, p.y);
    else
      cairo_line_to(cr, p.x, p.y);
  }
  cairo_close_path(cr);
}

// Ticks and labels along the floor edge from `a` to `b` (a straight axis of the box), on the
// side `outward` points to (a unit vector in pixels).
void edge_axis(cairo_t* cr, const SurfaceProjection& proj, Point3 a, Point3 b, Point outward,
               double lo, double hi, const std::string& label) {
  set_colour(cr, kBlack);
  cairo_set_line_width(cr, 1.0);
  move_line(cr, proj, a, b);
  cairo_stroke(cr);
  // About one tick per 50 px of the edge, so that a short edge keeps its labels apart.
  const Point pa = proj.project(a), pb = proj.project(b);
  const int target = std::clamp(static_cast<int>(std::hypot(pb.x - pa.x, pb.y - pa.y) / 50), 2, 5);
  const std::vector<double> ticks = nice_ticks(lo, hi, target);
  const double step = ticks.size() > 1 ? ticks[1] - ticks[0] : 1.0;
  const Align h = outward.x > 0.35 ? Align::start : outward.x < -0.35 ? Align::end : Align::centre;
  const Align v = outward.y > 0.35 ? Align::start : outward.y < -0.35 ? Align::end : Align::centre;
  for (double t : ticks) {
    const double f = hi > lo ? (t - lo) / (hi - lo) : 0.0;
    const Point p =
        proj.project({a.x + f * (b.x - a.x), a.y + f * (b.y - a.y), a.z + f * (b.z - a.z)});
    set_colour(cr, kBlack);
    cairo_move_to(cr, p.x, p.y);
    cairo_line_to(cr, p.x + 5 * outward.x, p.y + 5 * outward.y);
    cairo_stroke(cr);
    set_colour(cr, kTickText);
    text(cr, p.x + 9 * outward.x, p.y + 9 * outward.y, tick_label(t, step), 10, h, v);
  }
  const Point mid = proj.project({(a.x + b.x) / 2, (a.y + b.y) / 2, (a.z + b.z) / 2});
  set_colour(cr, kBlack);
  text(cr, mid.x + 34 * outward.x, mid.y + 34 * outward.y, label, 12, h, v);
}

}  // namespace

void draw_surface(cairo_t* cr, const SurfaceProjection& proj, const Raster& raster,
                  const ColourScale& colours, const SurfaceLabels& labels) {
  const Point3 lo = proj.lo(), hi = proj.hi();
  const double xm = (lo.x + hi.x) / 2, ym = (lo.y + hi.y) / 2, zm = (lo.z + hi.z) / 2;
  const bool x_hi_far = proj.depth({hi.x, ym, zm}) > proj.depth({lo.x, ym, zm});
  const bool y_hi_far = proj.depth({xm, hi.y, zm}) > proj.depth({xm, lo.y, zm});
  const double x_far = x_hi_far ? hi.x : lo.x, x_near = x_hi_far ? lo.x : hi.x;
  const double y_far = y_hi_far ? hi.y : lo.y, y_near = y_hi_far ? lo.y : hi.y;
  const std::vector<double> xt = nice_ticks(lo.x, hi.x, 5), yt = nice_ticks(lo.y, hi.y, 5),
                            zt = nice_ticks(lo.z, hi.z, 5);
  cairo_save(cr);
  cairo_set_dash(cr, nullptr, 0, 0.0);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);

  // The back panes: the floor and the two far walls, with grid lines at the ticks.
  const std::array<std::array<Point3, 4>, 3> panes{{
      {{{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {lo.x, hi.y, lo.z}}},
      {{{x_far, lo.y, lo.z}, {x_far, hi.y, lo.z}, {x_far, hi.y, hi.z}, {x_far, lo.y, hi.z}}},
      {{{lo.x, y_far, lo.z}, {hi.x, y_far, lo.z}, {hi.x, y_far, hi.z}, {lo.x, y_far, hi.z}}},
  }};
  for (const auto& p : panes) {
    pane(cr, proj, p);
    set_colour(cr, kPane);
    cairo_fill(cr);
  }
  for (double x : xt) {
    move_line(cr, proj, {x, lo.y, lo.z}, {x, hi.y, lo.z});
    move_line(cr, proj, {x, y_far, lo.z}, {x, y_far, hi.z});
  }
  for (double y : yt) {
    move_line(cr, proj, {lo.x, y, lo.z}, {hi.x, y, lo.z});
    move_line(cr, proj, {x_far, y, lo.z}, {x_far, y, hi.z});
  }
  for (double z : zt) {
    move_line(cr, proj, {x_far, lo.y, z}, {x_far, hi.y, z});
    move_line(cr, proj, {lo.x, y_far, z}, {hi.x, y_far, z});
  }
  set_colour(cr, kGrid);
  cairo_set_line_width(cr, 0.8);
  cairo_stroke(cr);
  for (const auto& p : panes)
    pane(cr, proj, p);
  set_colour(cr, kPaneEdge);
  cairo_stroke(cr);

  // The surface, farthest quads first.
  const std::vector<SurfaceQuad> quads = surface_quads(raster);
  cairo_set_line_width(cr, 0.5);
  for (std::size_t k : painter_order(quads, proj)) {
    std::array<Point3, 4> corners = quads[k].corners;
    for (Point3& c : corners)
      c.z = std::clamp(c.z, lo.z, hi.z);
    pane(cr, proj, corners);
    set_colour(cr, colours(quads[k].height));
    cairo_fill_preserve(cr);
    set_colour(cr, kQuadEdge, 0.35);
    cairo_stroke(cr);
  }

  // Axes: x and y along the floor's near edges, ticks pointing away from the floor's centre.
  const Point centre = proj.project({xm, ym, lo.z});
  auto away = [&](Point3 p) {
    const Point q = proj.project(p);
    const double dx = q.x - centre.x, dy = q.y - centre.y, len = std::hypot(dx, dy);
    return len > 0 ? Point{dx / len, dy / len} : Point{0, 1};
  };
  edge_axis(cr, proj, {lo.x, y_near, lo.z}, {hi.x, y_near, lo.z}, away({xm, y_near, lo.z}), lo.x,
            hi.x, labels.x);
  edge_axis(cr, proj, {x_near, lo.y, lo.z}, {x_near, hi.y, lo.z}, away({x_near, ym, lo.z}), lo.y,
            hi.y, labels.y);
  // z on the floor corner drawn leftmost, ticks to the left.
  Point3 corner{lo.x, lo.y, lo.z};
  for (const Point3& c : panes[0])
    if (proj.project(c).x < proj.project(corner).x) corner = c;
  set_colour(cr, kBlack);
  cairo_set_line_width(cr, 1.0);
  move_line(cr, proj, corner, {corner.x, corner.y, hi.z});
  cairo_stroke(cr);
  const double z_step = zt.size() > 1 ? zt[1] - zt[0] : 1.0;
  double widest = 0;
  for (double z : zt) {
    const Point p = proj.project({corner.x, corner.y, z});
    set_colour(cr, kBlack);
    cairo_move_to(cr, p.x, p.y);
    cairo_line_to(cr, p.x - 5, p.y);
    cairo_stroke(cr);
    // The floor's own level is left unlabelled: the y axis's last label sits there.
    if (z <= lo.z + 1e-9 * z_step) continue;
    const std::string s = tick_label(z, z_step);
    set_colour(cr, kTickText);
    text(cr, p.x - 8, p.y, s, 10, Align::end, Align::centre);
    widest = std::max(widest, static_cast<double>(s.size()) * 6.2);
  }
  const Point z_mid = proj.project({corner.x, corner.y, zm});
  set_colour(cr, kBlack);
  text(cr, z_mid.x - 16 - widest, z_mid.y, labels.z, 12, Align::centre, Align::end, false,
       -std::numbers::pi / 2);
  cairo_restore(cr);
}

}  // namespace masnet::scenarios::plot

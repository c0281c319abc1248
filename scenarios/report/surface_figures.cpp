// The pollution field of a diffusion run as a 3-D surface (left) beside its map with the robots
// (right), one figure per snapshot: the layout of the paper's Figs. 8–11 (docs/outputs.md).
#include <algorithm>
#include <cmath>
#include <limits>

#include <cairo.h>
#include <fmt/format.h>

#include "scenarios/report/figure_parts.hpp"
#include "scenarios/report/figures.hpp"
#include "scenarios/report/plot/plot_surface.hpp"

namespace masnet::scenarios::figure_parts {

void draw_pollution_surface(cairo_t* cr, const RunData& run, double t_s,
                            const plot::Raster& heights, const plot::ColourScale& colours,
                            double height_px, const std::function<void(cairo_t*)>& draw_map) {
  // The box: Ω's bounding box, and u from 0 (or below, if the field is) to this snapshot's peak.
  plot::Point3 lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                  0.0};
  plot::Point3 hi{-lo.x, -lo.y, -std::numeric_limits<double>::infinity()};
  for (const plot::Point& p : run.domain) {
    lo.x = std::min(lo.x, p.x);
    lo.y = std::min(lo.y, p.y);
    hi.x = std::max(hi.x, p.x);
    hi.y = std::max(hi.y, p.y);
  }
  if (!(hi.x > lo.x) || !(hi.y > lo.y)) {
    lo.x = heights.x0;
    lo.y = heights.y0;
    hi.x = heights.x1;
    hi.y = heights.y1;
  }
  for (double v : heights.values)
    if (std::isfinite(v)) {
      lo.z = std::min(lo.z, v);
      hi.z = std::max(hi.z, v);
    }
  const bool flat = !(hi.z > lo.z);
  const double peak = hi.z;
  if (flat) hi.z = lo.z + 1.0;

  const plot::SurfaceProjection projection({75, 80, kSurfacePanelPx - 135, height_px - 180}, lo,
                                           hi);
  plot::draw_surface(cr, projection, heights, colours,
                     {"x (world units)", "y (world units)", "pollution u"});
  cairo_set_source_rgb(cr, 0, 0, 0);
  const std::string when = snapshot_time_label(t_s);
  plot::text(cr, kSurfacePanelPx / 2, 40, fmt::format("{}: u(x, y) at t = {} s", run.name, when),
             14, plot::Align::centre, plot::Align::end, true);
  plot::text(cr, kSurfacePanelPx / 2, 58,
             std::isfinite(peak)
                 ? fmt::format("z axis up to this snapshot's peak, u = {:.4g}", peak)
                 : std::string("no field values"),
             11, plot::Align::centre, plot::Align::end);

  cairo_save(cr);
  cairo_translate(cr, kSurfacePanelPx, 0);
  draw_map(cr);
  cairo_restore(cr);
}

}  // namespace masnet::scenarios::figure_parts

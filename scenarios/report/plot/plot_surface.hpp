#pragma once
// A height field drawn as a 3-D surface: an orthographic (axonometric) projection of a box of
// data onto a pixel box, the raster's quads filled by height and drawn farthest first (the
// painter's algorithm), the box's back panes with grid lines, and three axes with ticks.
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "scenarios/report/plot/plot.hpp"

namespace masnet::scenarios::plot {

struct Point3 {
  double x = 0, y = 0, z = 0;
};

/// Where the viewer stands. `azimuth_rad`: seen from above, the viewer's direction measured
/// from the −y axis, counter-clockwise positive (0: in front, looking along +y; −37.5°: in front
/// and to the left). `elevation_rad`: the angle of the line of sight above the x-y plane
/// (0: level, 90°: from straight above).
struct View {
  double azimuth_rad = -0.6544984694978736;   // −37.5°
  double elevation_rad = 0.5235987755982988;  // 30°
};

/// Maps the box [lo, hi] to pixels: x and y keep the box's proportions (one scale for both),
/// the z extent is drawn `z_aspect` times the longer horizontal side, and the eight projected
/// corners are scaled to fit `frame` and centred in it. Orthographic: a line of sight is
/// (cos e·sin a, −cos e·cos a, sin e) from the box towards the viewer; the screen's right is
/// (cos a, sin a, 0) and its up (−sin e·sin a, sin e·cos a, cos e).
class SurfaceProjection {
 public:
  SurfaceProjection(Box frame, Point3 lo, Point3 hi, View view = {}, double z_aspect = 0.6);

  /// The pixel where `p` is drawn (y down).
  Point project(Point3 p) const;
  /// Distance along the line of sight in box units (the longer horizontal side is 1), from
  /// the box's centre; larger is farther from the viewer.
  double depth(Point3 p) const;
  const Point3& lo() const { return lo_; }
  const Point3& hi() const { return hi_; }

 private:
  // `p` in box units, centred on the box's centre.
  std::array<double, 3> centred(Point3 p) const;
  Point3 lo_, hi_;
  std::array<double, 3> extent_{};  // the box's sides in box units
  std::array<double, 3> right_{}, up_{}, toward_viewer_{};
  double scale_px_ = 1, centre_x_ = 0, centre_y_ = 0, mid_right_ = 0, mid_up_ = 0;
};

/// One quad of a surface: four corners in order around it and the height that colours it.
struct SurfaceQuad {
  std::array<Point3, 4> corners;
  double height = 0;  ///< the mean of the corners' heights
};

/// The quads between the centres of neighbouring raster cells (cell (i, j)'s centre at height
/// value (i, j)); a quad with a NaN corner is left out. At most `max_side` cells along each
/// side are used (every k-th, the last always kept), so that a fine raster does not become
/// tens of thousands of paths.
std::vector<SurfaceQuad> surface_quads(const Raster& raster, std::size_t max_side = 64);

/// The painter's order: indices of `quads` from the farthest (by the depth of each quad's
/// centre) to the nearest, ties by index, so that nearer quads cover farther ones.
std::vector<std::size_t> painter_order(const std::vector<SurfaceQuad>& quads,
                                       const SurfaceProjection& projection);

/// Axis labels of a surface, units in them.
struct SurfaceLabels {
  std::string x, y, z;
};

/// The back panes of the projection's box (the floor and the two far walls) with grid lines
/// at the ticks, the quads of `raster` in painter's order, filled by `colours` at their height
/// with thin edges (heights clamped to the box), then the x and y axes along the floor's near
/// edges and the z axis on its leftmost corner, with ticks and labels.
void draw_surface(cairo_t* cr, const SurfaceProjection& projection, const Raster& raster,
                  const ColourScale& colours, const SurfaceLabels& labels);

}  // namespace masnet::scenarios::plot

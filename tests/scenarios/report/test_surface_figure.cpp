// The 3-D surface of the pollution field: the projection against a camera built independently,
// the painter's order, and the surface figures of a short diffusion run.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <unistd.h>

#include "scenarios/report/plot/plot_surface.hpp"
#include "text_files.hpp"

namespace fs = std::filesystem;
using namespace masnet::scenarios::plot;
using masnet::test::count;
using masnet::test::slurp;

namespace {

constexpr double kDeg = std::numbers::pi / 180;
using Vec = std::array<double, 3>;

Vec cross(const Vec& a, const Vec& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const Vec& a, const Vec& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
Vec unit(const Vec& a) {
  const double n = std::sqrt(dot(a, a));
  return {a[0] / n, a[1] / n, a[2] / n};
}

// A look-at camera: the viewer's direction from the azimuth (from −y, counter-clockwise) and
// the elevation; the screen's right is up-axis × that direction, its up direction × right.
// Points are scaled to the box (longer horizontal side 1, z `z_aspect`), projected, and the
// eight corners fitted into the frame.
Point expected_pixel(Box frame, Point3 lo, Point3 hi, double azimuth, double elevation,
                     double z_aspect, Point3 p) {
  const Vec viewer{std::cos(elevation) * std::sin(azimuth),
                   -std::cos(elevation) * std::cos(azimuth), std::sin(elevation)};
  const Vec right = unit(cross({0, 0, 1}, viewer));
  const Vec up = cross(viewer, right);
  const double longer = std::max(hi.x - lo.x, hi.y - lo.y);
  auto box = [&](Point3 q) {
    return Vec{(q.x - (lo.x + hi.x) / 2) / longer, (q.y - (lo.y + hi.y) / 2) / longer,
               ((q.z - lo.z) / (hi.z - lo.z) - 0.5) * z_aspect};
  };
  double x_lo = 1e300, x_hi = -1e300, y_lo = 1e300, y_hi = -1e300;
  for (double x : {lo.x, hi.x})
    for (double y : {lo.y, hi.y})
      for (double z : {lo.z, hi.z}) {
        const Vec c = box({x, y, z});
        x_lo = std::min(x_lo, dot(c, right));
        x_hi = std::max(x_hi, dot(c, right));
        y_lo = std::min(y_lo, dot(c, up));
        y_hi = std::max(y_hi, dot(c, up));
      }
  const double s = std::min(frame.w / (x_hi - x_lo), frame.h / (y_hi - y_lo));
  const Vec c = box(p);
  return {frame.x + frame.w / 2 + s * (dot(c, right) - (x_lo + x_hi) / 2),
          frame.y + frame.h / 2 - s * (dot(c, up) - (y_lo + y_hi) / 2)};
}

SurfaceQuad flat_quad(double x0, double y0, double side, double z) {
  return {{{{x0, y0, z}, {x0 + side, y0, z}, {x0 + side, y0 + side, z}, {x0, y0 + side, z}}}, z};
}

}  // namespace

TEST_CASE("The surface projection maps known points of a front and a top view", "[scenarios]") {
  const Box frame{10, 20, 200, 100};
  // From the front, level: x to the right, z up, y along the line of sight. The unit cube's
  // front face is 1 × 1, so 100 px fit the frame's height; its centre is the frame's centre.
  const SurfaceProjection front(frame, {0, 0, 0}, {1, 1, 1}, View{0.0, 0.0}, 1.0);
  CHECK(front.project({1, 0.3, 1}).x == Approx(160));
  CHECK(front.project({1, 0.3, 1}).y == Approx(20));
  CHECK(front.project({0, 0.9, 0}).x == Approx(60));
  CHECK(front.project({0, 0.9, 0}).y == Approx(120));
  CHECK(front.project({0.5, 0.5, 0.5}).x == Approx(110));
  CHECK(front.project({0.5, 0.5, 0.5}).y == Approx(70));
  CHECK(front.depth({0.5, 1, 0.5}) == Approx(0.5));  // the back face is farther
  CHECK(front.depth({0.5, 0, 0.5}) == Approx(-0.5));
  // From straight above: a map, y up.
  const SurfaceProjection top(frame, {0, 0, 0}, {1, 1, 1}, View{0.0, 90 * kDeg}, 1.0);
  CHECK(top.project({1, 1, 0.7}).x == Approx(160));
  CHECK(top.project({1, 1, 0.7}).y == Approx(20));
  CHECK(top.project({0.25, 0, 0.2}).x == Approx(85));
  CHECK(top.project({0.25, 0, 0.2}).y == Approx(120));
  // From the +x side, level: y to the right.
  const SurfaceProjection side(frame, {0, 0, 0}, {1, 1, 1}, View{90 * kDeg, 0.0}, 1.0);
  CHECK(side.project({0.2, 1, 1}).x == Approx(160));
  CHECK(side.project({0.2, 1, 1}).y == Approx(20));
  CHECK(side.depth({0, 0.5, 0.5}) > side.depth({1, 0.5, 0.5}));
}

TEST_CASE("The surface projection agrees with a look-at camera for oblique views", "[scenarios]") {
  const Box frame{75, 80, 465, 420};
  const Point3 lo{0, 0, 0}, hi{2, 1, 5};  // a 2:1 floor, heights up to 5
  for (const auto& [azimuth, elevation] : std::vector<std::pair<double, double>>{
           {-37.5 * kDeg, 30 * kDeg}, {120 * kDeg, 55 * kDeg}, {-150 * kDeg, 10 * kDeg}}) {
    INFO("azimuth " << azimuth / kDeg << "°, elevation " << elevation / kDeg << "°");
    const SurfaceProjection projection(frame, lo, hi, View{azimuth, elevation}, 0.6);
    for (const Point3& p : {Point3{0, 0, 0}, Point3{2, 1, 5}, Point3{0.5, 0.25, 1},
                            Point3{2, 0, 2.5}, Point3{1.2, 0.9, 4}}) {
      const Point want = expected_pixel(frame, lo, hi, azimuth, elevation, 0.6, p);
      CHECK(projection.project(p).x == Approx(want.x).margin(1e-9));
      CHECK(projection.project(p).y == Approx(want.y).margin(1e-9));
    }
  }
  // The default view: from the front and to the left, so the corner (x0, y0) is nearest.
  const SurfaceProjection usual(frame, lo, hi);
  CHECK(usual.depth({0, 0, 0}) < usual.depth({2, 0, 0}));
  CHECK(usual.depth({0, 0, 0}) < usual.depth({0, 1, 0}));
  CHECK(usual.depth({2, 1, 0}) > usual.depth({2, 0, 0}));
}

TEST_CASE("Surface quads are drawn farthest first, whatever their heights", "[scenarios]") {
  const SurfaceProjection usual({0, 0, 400, 300}, {0, 0, 0}, {1, 1, 1});  // viewer at −x, −y
  // The near quad at (x0, y0) and the far one at (x1, y1): the far one first, also when the
  // near one is low and the far one tall (the ordering ignores height).
  CHECK(painter_order({flat_quad(0, 0, 0.1, 0.5), flat_quad(0.9, 0.9, 0.1, 0.5)}, usual) ==
        std::vector<std::size_t>{1, 0});
  CHECK(painter_order({flat_quad(0, 0, 0.1, 0.0), flat_quad(0.9, 0.9, 0.1, 1.0)}, usual) ==
        std::vector<std::size_t>{1, 0});
  CHECK(painter_order({flat_quad(0.9, 0.9, 0.1, 0.0), flat_quad(0, 0, 0.1, 1.0)}, usual) ==
        std::vector<std::size_t>{0, 1});
  // Seen from behind (+x, +y), the same two quads swap.
  const SurfaceProjection behind({0, 0, 400, 300}, {0, 0, 0}, {1, 1, 1},
                                 View{135 * kDeg, 30 * kDeg});
  CHECK(painter_order({flat_quad(0, 0, 0.1, 0.5), flat_quad(0.9, 0.9, 0.1, 0.5)}, behind) ==
        std::vector<std::size_t>{0, 1});
  // A row of quads across the line of sight keeps its index order (ties).
  const SurfaceProjection front({0, 0, 400, 300}, {0, 0, 0}, {1, 1, 1}, View{0.0, 30 * kDeg});
  CHECK(painter_order(
            {flat_quad(0.6, 0, 0.2, 0), flat_quad(0.2, 0, 0.2, 0), flat_quad(0.4, 0.5, 0.2, 0)},
            front) == std::vector<std::size_t>{2, 0, 1});
}

TEST_CASE("Surface quads join neighbouring cell centres and skip NaN corners", "[scenarios]") {
  Raster r;
  r.nx = 4;
  r.ny = 3;
  r.x0 = 0;
  r.x1 = 4;
  r.y0 = 0;
  r.y1 = 3;
  for (int k = 0; k < 12; ++k)
    r.values.push_back(k);
  std::vector<SurfaceQuad> quads = surface_quads(r);
  REQUIRE(quads.size() == 6);
  CHECK(quads[0].corners[0].x == 0.5);
  CHECK(quads[0].corners[0].y == 0.5);
  CHECK(quads[0].corners[2].x == 1.5);
  CHECK(quads[0].corners[2].y == 1.5);
  CHECK(quads[0].height == Approx((0 + 1 + 5 + 4) / 4.0));
  r.values[5] = std::numeric_limits<double>::quiet_NaN();  // cell (1, 1): four quads touch it
  CHECK(surface_quads(r).size() == 2);
  // A fine raster is thinned to at most `max_side` nodes per side, the last one kept.
  Raster fine;
  fine.nx = fine.ny = 160;
  fine.values.assign(160 * 160, 1.0);
  quads = surface_quads(fine, 64);
  CHECK(quads.size() <= 63 * 63);
  CHECK(quads.back().corners[2].x == Approx(159.5 / 160));
}

TEST_CASE("A short diffusion run writes a surface figure per snapshot, shown in its report",
          "[scenarios]") {
  const fs::path base =
      fs::temp_directory_path() / fmt::format("masnet-test-surface-{}", ::getpid());
  fs::remove_all(base);
  const fs::path dir = base / "run";
  const std::string command = fmt::format(
      "'{}/scenarios/masnet' run '{}/scenarios/paper/pollution_control.yaml' --out '{}' --set "
      "duration=1 --set 'output.snapshots=[0.5,1]' > '{}' 2>&1",
      MASNET_BINARY_DIR, MASNET_SOURCE_DIR, dir.string(), (base / "output.txt").string());
  fs::create_directories(base);
  const int status = std::system(command.c_str());
  INFO(slurp(base / "output.txt"));
  REQUIRE(status == 0);
  const std::string html = slurp(dir / "report.html");
  for (const char* t : {"0.5", "1.0"}) {
    const fs::path stem = dir / "figures" / (std::string("pollution_surface_t") + t);
    INFO(stem.string());
    const std::string png = slurp(fs::path(stem).concat(".png"));
    REQUIRE(png.size() > 24);
    // The surface panel (600 px) beside the field map of the unit square (680 × 600).
    auto be32 = [&](std::size_t at) {
      std::uint32_t v = 0;
      for (std::size_t k = 0; k < 4; ++k)
        v = v << 8 | static_cast<unsigned char>(png[at + k]);
      return v;
    };
    CHECK(be32(16) == 1280);
    CHECK(be32(20) == 600);
    const std::string svg = slurp(fs::path(stem).concat(".svg"));
    CHECK(count(svg, "<path ") > 900);  // 30 × 30 quads of the PDE grid, and the rest
    CHECK(slurp(fs::path(stem).concat(".pdf")).rfind("%PDF-", 0) == 0);
    // In the report's snapshot frame of its time, beside the cells and the field map.
    const std::size_t frame = html.find(fmt::format("id=\"snapshot-{}\"", t));
    REQUIRE(frame != std::string::npos);
    const std::size_t end = html.find("</div>", frame);
    const std::string frame_html = html.substr(frame, end - frame);
    CHECK(count(frame_html, "<img ") == 3);
    CHECK(frame_html.find(fmt::format("figures/pollution_surface_t{}.svg", t)) !=
          std::string::npos);
  }
  fs::remove_all(base);
}

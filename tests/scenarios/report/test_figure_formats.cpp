// The shape and the formats of the figures: maps sized to Ω's aspect ratio and filled by it,
// a PDF beside every PNG and SVG, byte-identical on every render (docs/outputs.md, figures/).
#include <catch2/catch.hpp>

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <cairo.h>
#include <fmt/format.h>

#include "scenarios/report/figures.hpp"
#include "scenarios/report/run_data.hpp"
#include "short_run.hpp"
#include "text_files.hpp"

namespace fs = std::filesystem;
using namespace masnet::scenarios;
using masnet::test::ShortRun;
using masnet::test::slurp;

namespace {

// A PNG's pixels as 0xRRGGBB, read back through Cairo.
struct Image {
  int width = 0, height = 0;
  std::vector<std::uint32_t> pixels;  // row-major
  std::uint32_t at(int x, int y) const {
    return pixels[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                  static_cast<std::size_t>(x)];
  }
};

Image read_png(const fs::path& path) {
  Image image;
  cairo_surface_t* surface = cairo_image_surface_create_from_png(path.c_str());
  if (cairo_surface_status(surface) == CAIRO_STATUS_SUCCESS) {
    cairo_surface_flush(surface);
    image.width = cairo_image_surface_get_width(surface);
    image.height = cairo_image_surface_get_height(surface);
    const int stride = cairo_image_surface_get_stride(surface);
    const unsigned char* data = cairo_image_surface_get_data(surface);
    for (int y = 0; y < image.height; ++y)
      for (int x = 0; x < image.width; ++x)
        image.pixels.push_back(reinterpret_cast<const std::uint32_t*>(
                                   data + static_cast<std::ptrdiff_t>(y) * stride)[x] &
                               0xFFFFFFu);
  }
  cairo_surface_destroy(surface);
  return image;
}

// A colour of the heat maps' yellow-orange-red scale: red well above blue. Nothing else on a
// map is (white background, grey grid, black text and cells, blue robots, green targets).
bool warm(std::uint32_t rgb) {
  const int r = static_cast<int>(rgb >> 16 & 0xFF), b = static_cast<int>(rgb & 0xFF);
  return r >= 128 && r - b >= 38;
}

// The first run of `true` from the start, bridging gaps of up to 3 (the grid lines drawn over
// a heat map); [first, last], or {-1, -1} when none.
std::pair<int, int> first_run(const std::vector<bool>& any) {
  int first = -1, last = -1;
  for (int i = 0; i < static_cast<int>(any.size()); ++i) {
    if (!any[static_cast<std::size_t>(i)]) continue;
    if (first >= 0 && i - last > 4) break;
    if (first < 0) first = i;
    last = i;
  }
  return {first, last};
}

// Width and height in pixels of the heat map of Ω: the warm pixels left of the colour bar
// (which has the same colours, 22 px to the right of the frame).
std::pair<int, int> heat_map_size(const Image& image) {
  std::vector<bool> columns(static_cast<std::size_t>(image.width), false);
  for (int x = 0; x < image.width; ++x)
    for (int y = 0; y < image.height && !columns[static_cast<std::size_t>(x)]; ++y)
      columns[static_cast<std::size_t>(x)] = warm(image.at(x, y));
  const auto [left, right] = first_run(columns);
  if (left < 0) return {0, 0};
  std::vector<bool> rows(static_cast<std::size_t>(image.height), false);
  for (int y = 0; y < image.height; ++y)
    for (int x = left; x <= right && !rows[static_cast<std::size_t>(y)]; ++x)
      rows[static_cast<std::size_t>(y)] = warm(image.at(x, y));
  const auto [top, bottom] = first_run(rows);
  return {right - left + 1, bottom - top + 1};
}

const ShortRun& square_run() {
  static const ShortRun run("figure-formats");
  return run;
}

}  // namespace

TEST_CASE("Maps of a 2:1 domain are twice as wide as tall and the domain fills them",
          "[scenarios]") {
  const ShortRun run("figures-wide", "--set 'domain.rectangle=[0,0,2,1]'");
  INFO(run.output);
  REQUIRE(run.status == 0);
  const fs::path figures = run.dir / "figures";
  for (const char* stem : {"snapshot_t1.0", "energy_map", "trajectories"}) {
    INFO(stem);
    const Image image = read_png(figures / (std::string(stem) + ".png"));
    REQUIRE(image.width > 0);
    // The long side keeps the unit square's 680 px; a square's map would be 600 or 640 tall.
    CHECK(image.width == 680);
    CHECK(image.height < 0.6 * image.width);
    if (std::string(stem) == "trajectories") continue;  // no heat map to measure
    const auto [w, h] = heat_map_size(image);
    INFO("heat map " << w << " x " << h << " px in " << image.width << " x " << image.height);
    CHECK(static_cast<double>(w) / h == Approx(2.0).epsilon(0.03));
    // Drawn as large as the unit square's (470 px frame), and no wide blank bands: in a
    // 680 × 600 image Ω took 37 % of the height (now 61 %, the energy map 55 %).
    CHECK(w >= 440);
    CHECK(h >= 0.5 * image.height);
  }
  // Curves keep their sizes.
  const Image curve = read_png(figures / "coverage_cost.png");
  CHECK(curve.width == 760);
  CHECK(curve.height == 560);
}

TEST_CASE("Maps of a 1:2 domain are twice as tall as wide and keep the long side", "[scenarios]") {
  const ShortRun run("figures-tall", "--set 'domain.rectangle=[0,0,1,2]'");
  INFO(run.output);
  REQUIRE(run.status == 0);
  const Image image = read_png(run.dir / "figures" / "snapshot_t1.0.png");
  REQUIRE(image.width > 0);
  CHECK(image.height == 600);
  CHECK(image.width < image.height);
  const auto [w, h] = heat_map_size(image);
  INFO("heat map " << w << " x " << h << " px in " << image.width << " x " << image.height);
  CHECK(static_cast<double>(h) / w == Approx(2.0).epsilon(0.03));
  CHECK(h >= 440);
}

TEST_CASE("Maps of the unit square keep their 680 px wide sizes", "[scenarios]") {
  const ShortRun& run = square_run();
  REQUIRE(run.status == 0);
  const fs::path figures = run.dir / "figures";
  for (const char* stem : {"snapshot_t0.5", "trajectories"}) {
    const Image image = read_png(figures / (std::string(stem) + ".png"));
    CHECK(image.width == 680);
    CHECK(image.height == 600);
  }
  const Image energy = read_png(figures / "energy_map.png");
  CHECK(energy.width == 680);
  CHECK(energy.height == 640);
  const auto [w, h] = heat_map_size(read_png(figures / "snapshot_t0.5.png"));
  CHECK(w == Approx(h).margin(2));
}

TEST_CASE("Every figure is also a PDF with the same bytes on every render", "[scenarios]") {
  const ShortRun& run = square_run();
  REQUIRE(run.status == 0);
  const fs::path figures = run.dir / "figures";
  std::size_t pngs = 0;
  for (const auto& entry : fs::directory_iterator(figures)) {
    if (entry.path().extension() != ".png") continue;
    ++pngs;
    const fs::path pdf = fs::path(entry.path()).replace_extension(".pdf");
    INFO(pdf.string());
    const std::string bytes = slurp(pdf);
    CHECK(bytes.rfind("%PDF-", 0) == 0);
    CHECK(bytes.size() > 2000);
    CHECK(bytes.substr(bytes.size() - 6) == "%%EOF\n");
    // Cairo would stamp the time of drawing; without it two renders match.
    CHECK(bytes.find("/CreationDate") == std::string::npos);
  }
  CHECK(pngs >= 10);

  // A second render, in this process, of the run's files gives every file's bytes again.
  const fs::path again = run.base / "figures-again";
  const std::vector<FigureInfo> drawn = write_figures(load_run_data(run.dir), again);
  std::size_t files = 0;
  for (const auto& entry : fs::directory_iterator(again)) {
    const std::string name = entry.path().filename().string();
    INFO(name);
    ++files;
    CHECK(slurp(entry.path()) == slurp(figures / name));
  }
  CHECK(files == 3 * drawn.size());
  CHECK(files == 3 * pngs);
}

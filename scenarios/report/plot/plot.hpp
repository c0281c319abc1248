#pragma once
// A tiny plotting layer over Cairo for the run's figures: axes with ticks and labels,
// polyline series, markers, bars, histograms, heat maps, a colour bar and a legend. Every
// figure is drawn by the same function on an SVG, a PNG and a PDF surface, so all three files
// always show the same picture. Coordinates: `Box` is in pixels (y down);
// data go through `Axes::px`/`Axes::py`.
#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

typedef struct _cairo
    cairo_t;  // NOLINT: Cairo's own spelling, so that users need not include cairo.h

namespace masnet::scenarios::plot {

struct Rgb {
  double r = 0, g = 0, b = 0;
};
struct Point {
  double x = 0, y = 0;
};
/// A rectangle in pixels, y pointing down.
struct Box {
  double x = 0, y = 0, w = 0, h = 0;
};

enum class Scale { linear, log };
enum class Marker { none, dot, cross, diamond, square };
enum class Align { start, centre, end };
enum class Placement { top_left, top_right, bottom_left, bottom_right, below };

/// How a line or an outline is stroked.
struct Style {
  Rgb colour;
  double width_px = 1.5;
  bool dashed = false;
  double alpha = 1.0;
};

/// Sequential colour map from light (u = 0) to dark (u = 1), ColorBrewer YlOrRd.
Rgb sequential(double u);
/// Distinct colours for series and robots (Tableau 10), cycling.
Rgb categorical(std::size_t i);

/// Maps values to colours through `sequential`, linearly or logarithmically; values outside
/// [lo, hi] are clamped (log: values ≤ 0 take the colour of lo).
struct ColourScale {
  double lo = 0, hi = 1;
  Scale scale = Scale::linear;
  double unit(double v) const;  ///< position in [0, 1]
  Rgb operator()(double v) const { return sequential(unit(v)); }
};

/// About `target` round tick values covering [lo, hi] (steps 1, 2, 5 × 10^k).
std::vector<double> nice_ticks(double lo, double hi, int target);
/// Decades inside [lo, hi] (lo > 0), with 2 and 5 in between when it spans under 2.5 decades.
std::vector<double> log_ticks(double lo, double hi);
/// Short label of a tick value: minimal decimals for `step`, k/M suffixes for large numbers.
std::string tick_label(double value, double step);

/// Toy-API text in DejaVu Sans, anchored at (x, y) by `h` and `v`; `angle_rad` rotates about it.
void text(cairo_t* cr, double x, double y, const std::string& s, double size_px,
          Align h = Align::start, Align v = Align::end, bool bold = false, double angle_rad = 0.0);

/// Values on a regular grid of cells covering [x0, x1] × [y0, y1]; row-major, row 0 at y0.
/// NaN cells are left transparent.
struct Raster {
  std::size_t nx = 0, ny = 0;
  double x0 = 0, y0 = 0, x1 = 1, y1 = 1;
  std::vector<double> values;
};

/// One plotting frame: data ranges, the mapping to pixels, and the legend entries of what
/// was drawn in it with a label.
class Axes {
 public:
  Axes(cairo_t* cr, Box frame);

  Axes& x_range(double lo, double hi, Scale scale = Scale::linear);
  Axes& y_range(double lo, double hi, Scale scale = Scale::linear);
  /// Shrinks the frame (centred) so that one data unit is as long on both axes (maps).
  Axes& equal_aspect();

  double px(double x) const;
  double py(double y) const;
  const Box& frame() const { return frame_; }

  /// Frame, light grid, ticks with labels and the axis labels (units in them).
  void decorate(const std::string& x_label, const std::string& y_label);
  /// Category names under the x axis at 0, 1, …, n − 1 (bar charts), instead of numeric ticks.
  void set_categories(std::vector<std::string> names) { categories_ = std::move(names); }
  void title(const std::string& s);
  /// Restricts drawing to the frame until `unclip`.
  void clip();
  void unclip();

  /// A polyline through (xs[i], ys[i]); NaN points break it. `label` adds a legend entry.
  void line(const std::vector<double>& xs, const std::vector<double>& ys, const Style& style,
            const std::string& label = {});
  /// A steps-after polyline (counts that change at sample times).
  void steps(const std::vector<double>& xs, const std::vector<double>& ys, const Style& style,
             const std::string& label = {});
  void polygon(const std::vector<Point>& points, const Style& style, bool closed = true);
  void filled_polygon(const std::vector<Point>& points, Rgb fill, double alpha = 1.0);
  /// Markers of `size_px`; `fill` inside, `edge` around (crosses use `edge` only).
  void markers(const std::vector<Point>& points, Marker marker, double size_px, Rgb fill, Rgb edge,
               const std::string& label = {});
  /// A circle of radius `r` in data units of x.
  void circle(Point centre, double r, const Style& style);
  /// An arrow from `from` to `to` (data) with a filled head of `head_px`.
  void arrow(Point from, Point to, const Style& style, double head_px = 9.0);
  /// Bars at x = 0, 1, … of the given values, each labelled with its value on top.
  void bars(const std::vector<double>& values, Rgb fill, const std::string& label = {});
  /// Histogram bars between consecutive `edges` with heights `counts`.
  void histogram(const std::vector<double>& edges, const std::vector<double>& counts, Rgb fill,
                 double alpha, const std::string& label = {});
  /// The raster painted as an image through `colours`, within the current clip.
  void heat_map(const Raster& raster, const ColourScale& colours);
  /// The legend of every labelled series drawn so far.
  void legend(Placement where = Placement::top_right);
  /// A legend entry for something drawn without a label (e.g. many polygons, one entry).
  void add_legend_entry(const std::string& label, const Style& style, Marker marker = Marker::none,
                        Rgb fill = {}, double marker_px = 0.0);

 private:
  struct Entry {
    std::string label;
    Style style;
    bool has_line = false;
    Marker marker = Marker::none;
    Rgb fill;
    Rgb edge;
    double marker_px = 0.0;
  };
  double map_x(double x) const;
  double map_y(double y) const;
  void draw_marker(double x, double y, Marker marker, double size_px, Rgb fill, Rgb edge) const;
  void draw_entry_sample(const Entry& e, double x, double y) const;

  cairo_t* cr_;
  Box frame_;
  double x_lo_ = 0, x_hi_ = 1, y_lo_ = 0, y_hi_ = 1;
  Scale x_scale_ = Scale::linear, y_scale_ = Scale::linear;
  std::vector<std::string> categories_;
  std::vector<Entry> legend_;
};

/// A vertical colour bar in `box` with ticks on its right and `label` along it.
void colour_bar(cairo_t* cr, Box box, const ColourScale& colours, const std::string& label);

/// Range [lo, hi] of the finite values, widened by `pad` of its span (log: by a factor);
/// a degenerate range is opened around its value. `log` ignores values ≤ 0.
std::pair<double, double> data_range(const std::vector<const std::vector<double>*>& series,
                                     double pad, bool log = false);

/// SVG elements to tag: a stroke colour reserved for one kind of element is replaced, in the
/// SVG text, by `class="name" id="name-k"` (k = 0, 1, … in drawing order). Cairo cannot put
/// attributes on what it draws, and tests and scripts want to find cells in the SVG.
struct SvgClass {
  Rgb stroke;
  std::string name;
};

/// Stores a file's bytes: the caller's writer, which throws when the file cannot be written.
using FileWriter = std::function<void(const std::filesystem::path&, std::string_view)>;

/// Writes `stem`.svg, `stem`.png and `stem`.pdf of `width` × `height` pixels through `write`
/// by calling `draw` three times (the PNG at `png_scale` device pixels per pixel, the PDF at
/// one point per pixel). The SVG's generated ids are renumbered and the PDF carries no
/// creation date, so that the same drawing gives byte-identical files in any process. Throws
/// std::runtime_error when Cairo fails, and whatever `write` throws.
void write_figure(const FileWriter& write, const std::filesystem::path& stem, double width,
                  double height, const std::function<void(cairo_t*)>& draw,
                  const std::vector<SvgClass>& classes = {}, double png_scale = 1.0);

/// The post-processing of write_figure on SVG text (exposed for tests).
std::string finish_svg(std::string svg, const std::vector<SvgClass>& classes);

}  // namespace masnet::scenarios::plot

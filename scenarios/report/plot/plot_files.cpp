// A figure drawn three times, into an SVG, a PNG and a PDF, whose bytes go to the caller's
// writer; the SVG made reproducible (renumbered ids) and its reserved strokes given classes.
#include <cmath>
#include <cstdint>
#include <map>
#include <string_view>

#include <cairo-pdf.h>
#include <cairo-svg.h>
#include <cairo.h>
#include <fmt/format.h>

#include "scenarios/report/plot/plot.hpp"

namespace masnet::scenarios::plot {

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

namespace {

// Draws on a vector surface made by `create` (which streams into `bytes`) and finishes it;
// throws when Cairo fails.
std::string vector_figure(const std::function<cairo_surface_t*(std::string*)>& create,
                          const std::function<void(cairo_t*)>& paint,
                          const std::filesystem::path& path) {
  std::string bytes;
  cairo_surface_t* surface = create(&bytes);
  cairo_t* cr = cairo_create(surface);
  paint(cr);
  const cairo_status_t drawn = cairo_status(cr);
  cairo_destroy(cr);
  cairo_surface_finish(surface);
  const cairo_status_t finished = cairo_surface_status(surface);
  cairo_surface_destroy(surface);
  check(drawn, path);
  check(finished, path);
  return bytes;
}

}  // namespace

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
  const std::filesystem::path pdf_path = std::filesystem::path(stem).concat(".pdf");
  {
    std::string svg = vector_figure(
        [&](std::string* bytes) {
          cairo_surface_t* surface =
              cairo_svg_surface_create_for_stream(append_to_string, bytes, width, height);
          cairo_svg_surface_set_document_unit(surface, CAIRO_SVG_UNIT_PX);
          return surface;
        },
        paint, svg_path);
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
  {
    // One pixel is one PDF point (1/72 in). Cairo stamps the creation time into the document
    // information; a date it cannot parse leaves it out, so that a re-render is byte-identical.
    const std::string pdf = vector_figure(
        [&](std::string* bytes) {
          cairo_surface_t* surface =
              cairo_pdf_surface_create_for_stream(append_to_string, bytes, width, height);
          cairo_pdf_surface_set_metadata(surface, CAIRO_PDF_METADATA_CREATE_DATE, "");
          return surface;
        },
        paint, pdf_path);
    write(pdf_path, pdf);
  }
}

}  // namespace masnet::scenarios::plot

#pragma once
// Shared by the plot layer's own files only: its colours and fonts, and how a Style becomes
// Cairo's state.
#include <limits>
#include <string>

#include <cairo.h>

#include "scenarios/report/plot/plot.hpp"

namespace masnet::scenarios::plot::detail {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
inline constexpr const char* kFont = "DejaVu Sans";
inline constexpr Rgb kBlack{0, 0, 0};
inline constexpr Rgb kGrid{0.88, 0.88, 0.88};
inline constexpr Rgb kTickText{0.15, 0.15, 0.15};

void set_colour(cairo_t* cr, Rgb c, double alpha = 1.0);
void apply_style(cairo_t* cr, const Style& s);
/// A number in at most three significant digits, with k or M for thousands and millions.
std::string compact_number(double v);

}  // namespace masnet::scenarios::plot::detail

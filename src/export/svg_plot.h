#pragma once
// Hand-written SVG for the HTML report: axes with "nice" ticks, text, line simplification.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "relief/geometry/types.h"

namespace relief::html {

// Linear map of data to pixels on one axis.
struct Scale {
  double d0, d1, p0, p1;
  [[nodiscard]] double operator()(double v) const { return p0 + (v - d0) / (d1 - d0) * (p1 - p0); }
};

// A plot area with data ranges; y grows up in data, down in pixels.
struct Axes {
  Scale x, y;
};

/// A "nice" tick step (1, 2 or 5 times a power of ten) giving about `count` ticks over `range`.
[[nodiscard]] double nice_step(double range, int count);
/// Decimals needed to print multiples of `step`.
[[nodiscard]] int decimals_for(double step);
/// Opens an <svg> of the given pixel size with an accessible title (`label`, already escaped).
void svg_open(std::string& h, double width, double height, std::string_view label, std::string_view cls = "");
/// A <text> element; `text_html` is already escaped, `extra` is appended to the attributes.
void svg_text(std::string& h, double x, double y, std::string_view anchor, const std::string& text_html,
              std::string_view extra = "");
/// Grid lines, axes, tick labels and axis titles for `a`.
void draw_axes(std::string& h, const Axes& a, std::string_view x_title, std::string_view y_title, int x_ticks,
               int y_ticks);

}  // namespace relief::html

#include "export/svg_plot.h"

#include <cmath>

#include "export/html_text.h"

namespace relief::html {

// A "nice" tick step (1, 2 or 5 times a power of ten) giving about `count` ticks over `range`.
double nice_step(double range, int count) {
  if (!(range > 0.0)) return 1.0;
  const double raw = range / count;
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  const double f = raw / mag;
  return (f < 1.5 ? 1.0 : f < 3.5 ? 2.0 : f < 7.5 ? 5.0 : 10.0) * mag;
}

int decimals_for(double step) {
  return step >= 1.0 ? 0 : static_cast<int>(std::ceil(-std::log10(step) - 1e-9));
}

void svg_open(std::string& h, double width, double height, std::string_view label, std::string_view cls) {
  h += "<svg viewBox=\"0 0 " + fixed(width, 0) + " " + fixed(height, 0) + "\" width=\"" + fixed(width, 0) +
       "\" height=\"" + fixed(height, 0) + "\" role=\"img\"";
  if (!cls.empty()) {
    h += " class=\"";
    h += cls;
    h += "\"";
  }
  h += "><title>";
  h += label;
  h += "</title>\n";
}

void svg_text(std::string& h, double x, double y, std::string_view anchor, const std::string& text_html,
              std::string_view extra) {
  h += "<text x=\"" + fixed(x, 1) + "\" y=\"" + fixed(y, 1) + "\" text-anchor=\"";
  h += anchor;
  h += "\"";
  h += extra;
  h += ">" + text_html + "</text>\n";
}

// Grid lines, axes and tick labels for `a`; `x_suffix`/`y_suffix` follow the labels.
void draw_axes(std::string& h, const Axes& a, std::string_view x_title, std::string_view y_title, int x_ticks,
               int y_ticks) {
  const double xs = nice_step(a.x.d1 - a.x.d0, x_ticks), ys = nice_step(a.y.d1 - a.y.d0, y_ticks);
  for (double v = std::ceil(a.y.d0 / ys - 1e-9) * ys; v <= a.y.d1 + 1e-9 * ys; v += ys) {
    const double py = a.y(v);
    h += "<line class=\"grid\" x1=\"" + fixed(a.x.p0, 1) + "\" x2=\"" + fixed(a.x.p1, 1) + "\" y1=\"" +
         fixed(py, 1) + "\" y2=\"" + fixed(py, 1) + "\"/>\n";
    svg_text(h, a.x.p0 - 5, py + 4, "end", fixed(v, decimals_for(ys)));
  }
  for (double v = std::ceil(a.x.d0 / xs - 1e-9) * xs; v <= a.x.d1 + 1e-9 * xs; v += xs) {
    const double px = a.x(v);
    h += "<line class=\"ax\" x1=\"" + fixed(px, 1) + "\" x2=\"" + fixed(px, 1) + "\" y1=\"" +
         fixed(a.y.p0, 1) + "\" y2=\"" + fixed(a.y.p0 + 4, 1) + "\"/>\n";
    svg_text(h, px, a.y.p0 + 16, "middle", fixed(v, decimals_for(xs)));
  }
  h += "<path class=\"ax\" fill=\"none\" d=\"M" + fixed(a.x.p0, 1) + " " + fixed(a.y.p1, 1) + "V" +
       fixed(a.y.p0, 1) + "H" + fixed(a.x.p1, 1) + "\"/>\n";
  svg_text(h, (a.x.p0 + a.x.p1) / 2, a.y.p0 + 31, "middle", std::string(x_title));
  svg_text(h, 12, (a.y.p0 + a.y.p1) / 2, "middle", std::string(y_title),
           " transform=\"rotate(-90 12 " + fixed((a.y.p0 + a.y.p1) / 2, 1) + ")\"");
}

}  // namespace relief::html

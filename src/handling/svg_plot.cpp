// The handling tests' plots (svg_plot.hpp).
#include "handling/svg_plot.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <fmt/format.h>

namespace dentsph::handling {

namespace {

constexpr double kWidth = 640, kHeight = 420;
constexpr double kLeft = 80, kRight = 20, kTop = 40, kBottom = 60;  // margins around the plot's frame
constexpr const char* kColours[] = {"#1f5fa8", "#c0392b", "#2e8b57", "#8e44ad", "#d35400"};

std::string escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '&') out += "&amp;";
    else if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else out += c;
  }
  return out;
}

// One axis: its data range and scale, from data to pixels.
struct Axis {
  bool log = false;
  double lo = 0, hi = 1;  // in data units (log: positive)
  double px0 = 0, px1 = 1;
  double step = 1;  // between ticks (linear)

  double t(double v) const { return log ? std::log10(v) : v; }
  double to_px(double v) const { return px0 + (t(v) - t(lo)) / (t(hi) - t(lo)) * (px1 - px0); }
  bool usable(double v) const { return std::isfinite(v) && (!log || v > 0); }
};

// A "nice" step for about `n` ticks over [lo, hi]: 1, 2 or 5 times a power of ten.
double nice_step(double lo, double hi, int n) {
  const double raw = (hi - lo) / n;
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * p >= raw) return m * p;
  return 10 * p;
}

// Fits the axis around `values` (at least one usable): decades on a log axis, nice steps with a
// margin on a linear one that includes 0 where the data are all of one sign and near it.
void fit(Axis& a, const std::vector<double>& values) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (double v : values)
    if (a.usable(v)) lo = std::min(lo, v), hi = std::max(hi, v);
  if (!std::isfinite(lo)) lo = a.log ? 1 : 0, hi = a.log ? 10 : 1;
  if (a.log) {
    a.lo = std::pow(10.0, std::floor(std::log10(lo)));
    a.hi = std::pow(10.0, std::ceil(std::log10(hi)));
    if (a.hi <= a.lo) a.hi = 10 * a.lo;
    return;
  }
  if (lo > 0 && lo < 0.5 * hi) lo = 0;
  if (hi < 0 && hi > 0.5 * lo) hi = 0;
  if (hi <= lo) hi = lo + (lo == 0 ? 1 : std::abs(lo) * 0.1);
  a.step = nice_step(lo, hi, 5);
  a.lo = std::floor(lo / a.step) * a.step;
  a.hi = std::ceil(hi / a.step) * a.step;
}

std::vector<double> ticks(const Axis& a) {
  std::vector<double> t;
  if (a.log) {
    for (double v = a.lo; v <= a.hi * 1.0001; v *= 10) t.push_back(v);
    return t;
  }
  const long first = std::lround(a.lo / a.step), last = std::lround(a.hi / a.step);
  for (long k = first; k <= last; ++k) t.push_back(double(k) * a.step);
  return t;
}

std::string tick_label(double v) {
  if (v == 0) return "0";
  const double a = std::abs(v);
  if (a >= 1e6 || a < 1e-3) return fmt::format("{:.0e}", v);
  return fmt::format("{:g}", v);
}

}  // namespace

std::string svg_plot(const HandlingCurve& curve) {
  Axis x{curve.log_x}, y{curve.log_y};
  std::vector<double> xs, ys;
  for (const HandlingSeries& s : curve.series) {
    xs.insert(xs.end(), s.x.begin(), s.x.end());
    ys.insert(ys.end(), s.y.begin(), s.y.end());
  }
  if (curve.range_bar) {
    xs.push_back((*curve.range_bar)[0]);
    ys.push_back((*curve.range_bar)[1]);
    ys.push_back((*curve.range_bar)[2]);
  }
  fit(x, xs);
  fit(y, ys);
  x.px0 = kLeft, x.px1 = kWidth - kRight;
  y.px0 = kHeight - kBottom, y.px1 = kTop;

  std::string svg = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0}\" height=\"{1}\" viewBox=\"0 0 {0} {1}\" "
      "font-family=\"DejaVu Sans, Arial, sans-serif\" font-size=\"13\">\n"
      "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
      "<text x=\"{2}\" y=\"24\" text-anchor=\"middle\" font-size=\"15\" font-weight=\"bold\">{3}</text>\n",
      kWidth, kHeight, 0.5 * (kLeft + kWidth - kRight), escape(curve.title));
  // Grid lines and tick labels.
  for (double v : ticks(x)) {
    const double px = x.to_px(v);
    svg += fmt::format("<line x1=\"{0:.1f}\" y1=\"{1}\" x2=\"{0:.1f}\" y2=\"{2}\" stroke=\"#e3e3e3\"/>\n", px, kTop,
                       kHeight - kBottom);
    svg += fmt::format("<text x=\"{:.1f}\" y=\"{}\" text-anchor=\"middle\">{}</text>\n", px, kHeight - kBottom + 18,
                       tick_label(v));
  }
  for (double v : ticks(y)) {
    const double py = y.to_px(v);
    svg += fmt::format("<line x1=\"{0}\" y1=\"{1:.1f}\" x2=\"{2}\" y2=\"{1:.1f}\" stroke=\"#e3e3e3\"/>\n", kLeft, py,
                       kWidth - kRight);
    svg += fmt::format("<text x=\"{}\" y=\"{:.1f}\" text-anchor=\"end\">{}</text>\n", kLeft - 6, py + 4, tick_label(v));
  }
  svg += fmt::format("<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"#333\"/>\n", kLeft, kTop,
                     kWidth - kLeft - kRight, kHeight - kTop - kBottom);
  svg += fmt::format("<text x=\"{:.1f}\" y=\"{}\" text-anchor=\"middle\">{}</text>\n", 0.5 * (kLeft + kWidth - kRight),
                     kHeight - 16, escape(curve.x_label));
  svg += fmt::format("<text transform=\"translate(18 {:.1f}) rotate(-90)\" text-anchor=\"middle\">{}</text>\n",
                     0.5 * (kTop + kHeight - kBottom), escape(curve.y_label));
  // The legend, an entry a line; then the published range and the series, each with its entry.
  int legend = 0;
  auto legend_entry = [&](const std::string& name, const std::string& colour, const std::string& dash) {
    const double ly = kTop + 14 + 18 * legend++;
    const double lx = curve.legend_right ? kWidth - kRight - 190 : kLeft + 12;
    svg += fmt::format("<line x1=\"{}\" y1=\"{:.1f}\" x2=\"{}\" y2=\"{:.1f}\" stroke=\"{}\" stroke-width=\"2.5\"{}/>\n",
                       lx, ly, lx + 28, ly, colour, dash);
    svg += fmt::format("<text x=\"{}\" y=\"{:.1f}\">{}</text>\n", lx + 34, ly + 4, escape(name));
  };
  if (curve.range_bar && x.usable((*curve.range_bar)[0]) && y.usable((*curve.range_bar)[1]) &&
      y.usable((*curve.range_bar)[2])) {
    const double px = x.to_px((*curve.range_bar)[0]);
    const double p_lo = y.to_px((*curve.range_bar)[1]), p_hi = y.to_px((*curve.range_bar)[2]);
    svg += fmt::format("<rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"12\" height=\"{:.1f}\" fill=\"#f5b041\" "
                       "fill-opacity=\"0.55\" stroke=\"#b9770e\"/>\n",
                       px - 6, p_hi, p_lo - p_hi);
    legend_entry("published range", "#f5b041", "");
  }
  // The series: a polyline of the usable points, with a dot at each measured one.
  int colour = 0;
  for (const HandlingSeries& s : curve.series) {
    const std::string c = kColours[colour++ % std::size(kColours)];
    std::string points;
    std::string dots;
    for (std::size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
      if (!x.usable(s.x[i]) || !y.usable(s.y[i])) continue;
      const double px = x.to_px(s.x[i]), py = y.to_px(s.y[i]);
      points += fmt::format("{:.1f},{:.1f} ", px, py);
      if (!s.dashed && s.x.size() <= 12) dots += fmt::format("<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"3.5\" fill=\"{}\"/>\n", px, py, c);
    }
    const std::string dash = s.dashed ? " stroke-dasharray=\"7 5\"" : "";
    svg += fmt::format("<polyline points=\"{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"2\"{}/>\n", points, c, dash);
    svg += dots;
    legend_entry(s.name, c, dash);
  }
  svg += "</svg>\n";
  return svg;
}

}  // namespace dentsph::handling

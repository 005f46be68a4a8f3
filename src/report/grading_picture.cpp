// The surface's grading as a picture (grading_picture.hpp).
#include "report/grading_picture.hpp"

#include <algorithm>
#include <fstream>
#include <stdexcept>

#include <fmt/format.h>

namespace dentsph::report {

namespace {

constexpr double kPxPerMm = 90;
constexpr double kPad = 30;       // px round the opening
constexpr double kLegend = 250;   // px of legend on the right

// The bands' colours, deepest under-contour first (deviation_colour's order).
constexpr const char* kBands[] = {"#08306b", "#2171b5", "#9ecae1", "#d9f0d3", "#fdd0a2", "#f16913", "#7f2704"};

// The margin's readings (surface_grade.hpp: 0 sound, 1 gap, 2 excess, 3 open).
constexpr const char* kReading[] = {"#1b7837", "#d6191b", "#762a83", "#969696"};
constexpr const char* kReadingLabel[] = {"margin sound", "margin: gap", "margin: excess", "proximal opening (not graded)"};

}  // namespace

const char* deviation_colour(double d, double alpha, double charlie) {
  const double twice = std::min(2 * alpha, charlie);
  if (d < -charlie) return kBands[0];
  if (d < -twice) return kBands[1];
  if (d < -alpha) return kBands[2];
  if (d <= alpha) return kBands[3];
  if (d <= twice) return kBands[4];
  if (d <= charlie) return kBands[5];
  return kBands[6];
}

std::string grading_svg(const SurfaceGrade& g) {
  const AnatomicForm& a = g.anatomic;
  const MarginalAdaptation& m = g.margin;
  if (!a.measured && !m.measured) return "";
  // The extent of what is drawn, in mm of the tooth frame (x to the right: mesial; y up).
  double x0 = 1e9, x1 = -1e9, y0 = 1e9, y1 = -1e9;
  auto grow = [&](const Vec3& p) {
    x0 = std::min(x0, p.x), x1 = std::max(x1, p.x), y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
  };
  for (const Vec3& c : a.column_centre_mm) grow(c);
  for (const Vec3& p : m.point_mm) grow(p);
  const double w = (x1 - x0) * kPxPerMm + 2 * kPad + kLegend, h = std::max((y1 - y0) * kPxPerMm + 2 * kPad + 40, 260.0);
  auto px = [&](double x) { return kPad + (x - x0) * kPxPerMm; };
  auto py = [&](double y) { return kPad + 30 + (y1 - y) * kPxPerMm; };
  std::string s = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{:.0f}\" height=\"{:.0f}\" viewBox=\"0 0 {:.0f} {:.0f}\" "
      "font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" fill=\"#fafafa\"/>\n",
      w, h, w, h);
  s += fmt::format("<text x=\"{:.0f}\" y=\"20\" font-size=\"13\">The restoration against the intact tooth, from above "
                   "(anatomic form {}; margin {})</text>\n",
                   kPad, a.measured ? anatomic_band_name(a.band) : "not measured",
                   m.measured ? fmt::format("{} site{}", m.defects.size(), m.defects.size() == 1 ? "" : "s") : "not measured");
  const double cell = a.column_mm * kPxPerMm;
  for (std::size_t k = 0; k < a.column_centre_mm.size(); ++k) {
    const Vec3& c = a.column_centre_mm[k];
    s += fmt::format("<rect class=\"column\" x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.2f}\" height=\"{:.2f}\" fill=\"{}\"/>\n",
                     px(c.x) - cell / 2, py(c.y) - cell / 2, cell + 0.3, cell + 0.3,
                     deviation_colour(a.deviation_mm[k], a.alpha_max_mm, a.charlie_under_mm));
  }
  for (std::size_t k = 0; k < m.point_mm.size(); ++k) {
    const int r = std::clamp(m.reading[k], 0, 3);
    s += fmt::format("<circle class=\"margin r{}\" cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"{}\" fill=\"{}\"/>\n", r,
                     px(m.point_mm[k].x), py(m.point_mm[k].y), r == 0 ? 1.5 : 2.5, kReading[r]);
  }
  // The 1 mm bar and the mesial arrow, under the opening.
  const double by = py(y0) + 18;
  s += fmt::format("<line x1=\"{:.0f}\" y1=\"{:.0f}\" x2=\"{:.0f}\" y2=\"{:.0f}\" stroke=\"#333\" stroke-width=\"2\"/>"
                   "<text x=\"{:.0f}\" y=\"{:.0f}\">1 mm</text>\n",
                   kPad, by, kPad + kPxPerMm, by, kPad + kPxPerMm + 6, by + 4);
  s += fmt::format("<text x=\"{:.0f}\" y=\"{:.0f}\" text-anchor=\"end\">mesial &#8594;</text>\n", px(x1), by + 4);
  // The legend.
  const double lx = w - kLegend + 10;
  double ly = 50;
  auto key = [&](const char* colour, const std::string& label, bool dot) {
    s += dot ? fmt::format("<circle cx=\"{:.0f}\" cy=\"{:.0f}\" r=\"4\" fill=\"{}\"/>", lx + 7, ly - 4, colour)
             : fmt::format("<rect x=\"{:.0f}\" y=\"{:.0f}\" width=\"14\" height=\"12\" fill=\"{}\"/>", lx, ly - 10, colour);
    s += fmt::format("<text x=\"{:.0f}\" y=\"{:.0f}\">{}</text>\n", lx + 20, ly, label);
    ly += 18;
  };
  const double alpha = a.alpha_max_mm, twice = std::min(2 * alpha, a.charlie_under_mm), charlie = a.charlie_under_mm;
  if (a.measured) {
    s += fmt::format("<text x=\"{:.0f}\" y=\"{:.0f}\" font-weight=\"bold\">deviation from the intact tooth</text>\n", lx, ly - 14);
    ly += 6;
    key(kBands[0], fmt::format("deeper than {:.2f} mm (charlie)", charlie), false);
    key(kBands[1], fmt::format("{:.2f} to {:.2f} mm under", twice, charlie), false);
    key(kBands[2], fmt::format("{:.2f} to {:.2f} mm under", alpha, twice), false);
    key(kBands[3], fmt::format("within {:.2f} mm (alpha)", alpha), false);
    key(kBands[4], fmt::format("{:.2f} to {:.2f} mm over", alpha, twice), false);
    key(kBands[5], fmt::format("{:.2f} to {:.2f} mm over", twice, charlie), false);
    key(kBands[6], fmt::format("more than {:.2f} mm over", charlie), false);
    ly += 8;
  }
  if (m.measured)
    for (int r = 0; r < 4; ++r) key(kReading[r], kReadingLabel[r], true);
  return s + "</svg>\n";
}

void write_grading_picture(const std::filesystem::path& dir, const SurfaceGrade& g) {
  const std::string svg = grading_svg(g);
  if (svg.empty()) return;
  const std::filesystem::path file = dir / kGradingPicture;
  std::ofstream out(file, std::ios::binary);
  out << svg;
  if (!out) throw std::runtime_error(fmt::format("{}: cannot write the grading's picture", file.string()));
}

}  // namespace dentsph::report

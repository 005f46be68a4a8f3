// The surface's grading as a picture (docs/report.md, "The pictures"): the cavity's opening seen
// from above along the tooth's long axis, each column of the anatomic form coloured by its
// deviation from the intact tooth in the bands the report judges (under-contoured in blues, within
// alpha in pale green, over-contoured in oranges), the margin's points by their reading (sound,
// gap, excess, open), a legend and a 1 mm bar. SVG: a tutor's browser scales it, and its text is
// text.
#pragma once

#include <filesystem>
#include <string>

#include "dentsph/surface_grade.hpp"

namespace dentsph::report {

inline constexpr const char* kGradingPicture = "grading.svg";

// The picture of `g` (empty when neither criterion was measured).
std::string grading_svg(const SurfaceGrade& g);

// The colour of a column `deviation_mm` from the intact tooth, by band edges at alpha_max_mm, twice
// it and charlie_under_mm ("#rrggbb").
const char* deviation_colour(double deviation_mm, double alpha_max_mm, double charlie_under_mm);

// Writes DIR/grading.svg (nothing when the picture is empty). Throws std::runtime_error naming the
// file when it cannot be written.
void write_grading_picture(const std::filesystem::path& dir, const SurfaceGrade& g);

}  // namespace dentsph::report

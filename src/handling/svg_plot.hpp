// A curve of a handling test as an SVG plot (axes with their ticks and labels, a legend, a
// published range as a bar): a picture a browser or docs/model.md shows as it is, with no library.
#pragma once

#include <string>

#include "dentsph/handling.hpp"

namespace dentsph::handling {

// The plot of `curve`, 640 x 420 px. Non-positive values on a log axis and non-finite values are
// left out of the series they are in.
std::string svg_plot(const HandlingCurve& curve);

}  // namespace dentsph::handling

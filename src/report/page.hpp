// The frame every report page shares: one self-contained HTML document (styles inline, the
// plotting library inline, no network), and the badge of a verdict.
#pragma once

#include <string>
#include <string_view>

#include "report/criteria.hpp"

namespace dentsph::report {

// <!DOCTYPE html> ... <body> with the styles and Chart.js inlined.
std::string page_begin(std::string_view title);
std::string page_end();
// <span class="verdict good">good</span>
std::string verdict_badge(Verdict v);
// The value cell of a criterion: its shown text, with the number as the file holds it in
// data-key / data-value (the tests compare these with the files).
std::string value_cell(const Criterion& c);

}  // namespace dentsph::report

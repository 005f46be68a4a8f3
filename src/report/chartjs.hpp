// Chart.js, the plotting library the report bundles into its HTML (Debian's libjs-chart.js,
// read at build time: the report needs no network and no file at run time).
#pragma once

#include <string>
#include <string_view>

namespace dentsph::report {

// The minified library (chart.min.js), whole.
const std::string& chartjs_source();
// Its version, from the file's header ("3.9.1").
std::string_view chartjs_version();

}  // namespace dentsph::report

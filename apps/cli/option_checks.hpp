// Numeric options checked for what they are: a finite number within the range the program can
// use. CLI11's PositiveNumber and Range let "nan" through (NaN compares false with every bound),
// and "1e308" is positive: --force-scale nan was replaced by the default without a word, and
// --stiffness 1e308 rendered 0 N a whole session. Out of range, the option is refused with its
// name, the value and the range (exit 2).
#pragma once

#include <cmath>
#include <string>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

namespace dentsph::cli {

// A finite number in [lo, hi].
inline CLI::Validator finite_range(double lo, double hi) {
  return CLI::Validator(
      [lo, hi](std::string& input) -> std::string {
        double v = 0;
        if (!CLI::detail::lexical_cast(input, v)) return fmt::format("Value {} is not a number", input);
        if (!std::isfinite(v) || v < lo || v > hi) return fmt::format("Value {} not in range {:g} to {:g}", input, lo, hi);
        return {};
      },
      fmt::format("FLOAT in [{:g} - {:g}]", lo, hi));
}

// A finite number in (0, hi].
inline CLI::Validator finite_positive(double hi) {
  return CLI::Validator(
      [hi](std::string& input) -> std::string {
        double v = 0;
        if (!CLI::detail::lexical_cast(input, v)) return fmt::format("Value {} is not a number", input);
        if (!std::isfinite(v) || !(v > 0) || v > hi) return fmt::format("Value {} not in range (0 to {:g}]", input, hi);
        return {};
      },
      fmt::format("FLOAT in (0 - {:g}]", hi));
}

}  // namespace dentsph::cli

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

// A finite number in [lo, hi], or in (lo, hi] with `open_below`; `range` says which for a person.
inline CLI::Validator finite_number(double lo, double hi, bool open_below, std::string range) {
  return CLI::Validator(
      [lo, hi, open_below, range](std::string& input) -> std::string {
        double v = 0;
        if (!CLI::detail::lexical_cast(input, v)) return fmt::format("Value {} is not a number", input);
        if (!std::isfinite(v) || v < lo || (open_below && v == lo) || v > hi)
          return fmt::format("Value {} not in range {}", input, range);
        return {};
      },
      "FLOAT in " + range);
}

// A finite number in [lo, hi].
inline CLI::Validator finite_range(double lo, double hi) {
  return finite_number(lo, hi, false, fmt::format("{:g} to {:g}", lo, hi));
}

// A finite number in (0, hi] (no upper bound without `hi`: a later check names the limit).
inline CLI::Validator finite_positive(double hi = HUGE_VAL) {
  return finite_number(0, hi, true,
                       std::isfinite(hi) ? fmt::format("(0 to {:g}]", hi) : std::string("above 0, finite"));
}

// Where `text` stops being UTF-8 (its length when it is), by the encoding's rules: no stray
// continuation bytes, no overlong forms, no surrogates, nothing above U+10FFFF.
inline std::size_t utf8_error_at(const std::string& text) {
  const auto* p = reinterpret_cast<const unsigned char*>(text.data());
  const std::size_t n = text.size();
  std::size_t i = 0;
  while (i < n) {
    const unsigned c = p[i];
    std::size_t len = 0;
    unsigned lo = 0x80, hi = 0xBF;  // the second byte's range
    if (c < 0x80) len = 1;
    else if (c >= 0xC2 && c <= 0xDF) len = 2;
    else if (c == 0xE0) len = 3, lo = 0xA0;
    else if (c >= 0xE1 && c <= 0xEC) len = 3;
    else if (c == 0xED) len = 3, hi = 0x9F;
    else if (c >= 0xEE && c <= 0xEF) len = 3;
    else if (c == 0xF0) len = 4, lo = 0x90;
    else if (c >= 0xF1 && c <= 0xF3) len = 4;
    else if (c == 0xF4) len = 4, hi = 0x8F;
    else return i;
    if (i + len > n) return i;
    for (std::size_t k = 1; k < len; ++k) {
      const unsigned b = p[i + k];
      if (k == 1 ? (b < lo || b > hi) : (b < 0x80 || b > 0xBF)) return i;
    }
    i += len;
  }
  return n;
}

// A name a person gave (a student, an exercise): UTF-8 (it goes into JSON, HTML and the session
// store), no control characters, at most `max_bytes`. Checked before the session runs, so that a
// name never loses a session at its end.
inline CLI::Validator person_text(std::size_t max_bytes = 200) {
  return CLI::Validator(
      [max_bytes](std::string& input) -> std::string {
        const std::size_t bad = utf8_error_at(input);
        if (bad < input.size())
          return fmt::format("not UTF-8 text: byte 0x{:02X} at position {}; give it in UTF-8 (a terminal or file in "
                             "Latin-1 sends such bytes)",
                             unsigned(static_cast<unsigned char>(input[bad])), bad);
        for (std::size_t i = 0; i < input.size(); ++i)
          if (static_cast<unsigned char>(input[i]) < 0x20 || input[i] == 0x7F)
            return fmt::format("a control character at position {}; give plain text", i);
        if (input.size() > max_bytes) return fmt::format("{} bytes; at most {}", input.size(), max_bytes);
        return {};
      },
      "TEXT (UTF-8)");
}

}  // namespace dentsph::cli

// Progress of a long run for a person: on a terminal a bar redrawn in place with the rate and the
// time left; otherwise (a log, CI) a plain line every few seconds.
#pragma once

#include <cstdio>
#include <string>

#include <fmt/format.h>
#include <unistd.h>

#include "dentsph/run.hpp"

namespace dentsph::cli {

class ProgressReporter {
 public:
  explicit ProgressReporter(std::FILE* out = stderr) : out_(out), terminal_(isatty(fileno(out)) != 0) {}

  void operator()(const RunProgress& p) {
    const bool last = p.step == p.total;
    const double every = terminal_ ? 0.1 : 5.0;  // s of wall time between updates
    if (!last && p.wall_s - last_print_ < every) return;
    last_print_ = p.wall_s;
    const double frac = p.total ? double(p.step) / double(p.total) : 1.0;
    const double rate = p.wall_s > 0 ? double(p.step) / p.wall_s : 0.0;
    if (terminal_) {
      constexpr int width = 30;
      const int filled = int(frac * width + 0.5);
      fmt::print(out_, "\r[{}{}] {:5.1f}%  step {}/{}  t = {:.3f} s  {:.0f} steps/s  ETA {}   ",
                 std::string(std::size_t(filled), '#'), std::string(std::size_t(width - filled), '.'), 100 * frac,
                 p.step, p.total, p.sim_time, rate, clock(p.eta_s));
      if (last) fmt::print(out_, "\n");
    } else {
      fmt::print(out_, "progress {:5.1f}%  step {}/{}  t = {:.3f} s  {:.0f} steps/s  ETA {}\n", 100 * frac, p.step,
                 p.total, p.sim_time, rate, clock(p.eta_s));
    }
    std::fflush(out_);
  }

  // "1:05" for 65 s, "1:01:05" past an hour.
  static std::string clock(double seconds) {
    const long s = long(seconds + 0.5);
    return s >= 3600 ? fmt::format("{}:{:02d}:{:02d}", s / 3600, (s / 60) % 60, s % 60)
                     : fmt::format("{}:{:02d}", s / 60, s % 60);
  }

 private:
  std::FILE* out_;
  bool terminal_;
  double last_print_ = -1e9;
};

}  // namespace dentsph::cli

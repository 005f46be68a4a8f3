// force_spectrum (haptics.hpp): the spectrum of the force rendered to the device, above a cutoff.
#include <fftw3.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstddef>
#include <mutex>
#include <numbers>
#include <vector>

#include "dentsph/haptics.hpp"

namespace dentsph {

namespace {

constexpr std::size_t kMinTicks = 64;

// FFTW's planner is not thread-safe (its plans' execution is): plans are made and destroyed
// under one lock.
std::mutex& planner_mutex() {
  static std::mutex m;
  return m;
}

class RealFft {
 public:
  explicit RealFft(std::size_t n) : in_(n), out_(n / 2 + 1) {
    const std::lock_guard<std::mutex> lock(planner_mutex());
    plan_ = fftw_plan_dft_r2c_1d(int(n), in_.data(), reinterpret_cast<fftw_complex*>(out_.data()), FFTW_ESTIMATE);
  }
  ~RealFft() {
    const std::lock_guard<std::mutex> lock(planner_mutex());
    fftw_destroy_plan(plan_);
  }
  RealFft(const RealFft&) = delete;
  RealFft& operator=(const RealFft&) = delete;
  std::vector<double>& in() { return in_; }
  const std::vector<std::complex<double>>& run() {
    fftw_execute(plan_);
    return out_;
  }

 private:
  std::vector<double> in_;
  std::vector<std::complex<double>> out_;
  fftw_plan plan_ = nullptr;
};

// The nominal rate, or (when the recording has none) the median tick period's.
double sampling_rate(const Recording& r) {
  if (r.haptic_rate_hz > 0 && std::isfinite(r.haptic_rate_hz)) return r.haptic_rate_hz;
  std::vector<double> periods;
  for (std::size_t k = 1; k < r.haptic.size(); ++k) periods.push_back(r.haptic[k].t - r.haptic[k - 1].t);
  if (periods.empty()) return 0;
  const auto mid = periods.begin() + std::ptrdiff_t(periods.size() / 2);
  std::nth_element(periods.begin(), mid, periods.end());
  return *mid > 0 && std::isfinite(*mid) ? 1 / *mid : 0;
}

bool finite(const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// The force the device held at the middle of each period of `rate` from the first tick on: each
// tick's force holds until the next tick (a non-finite one, which the limiter never passes, keeps
// the previous). Three series, one per axis.
std::array<std::vector<double>, 3> held_force(const std::vector<HapticSample>& ticks, double rate) {
  std::array<std::vector<double>, 3> f;
  const double t0 = ticks.front().t, span = ticks.back().t - t0, period = 1 / rate;
  if (!std::isfinite(span) || span < 0) return f;
  // Periods without a tick are held, but a recording whose times span far more periods than it has
  // ticks (hand-made, or a clock jump) is not a session's: not analysed rather than allocated for.
  if (span / period > 4.0 * double(ticks.size()) + 64) return f;
  const auto n = std::size_t(std::floor(span / period + 0.5)) + 1;
  for (auto& axis : f) axis.reserve(n);
  std::size_t k = 0;
  Vec3 held = finite(ticks[0].force) ? ticks[0].force : Vec3{};
  for (std::size_t j = 0; j < n; ++j) {
    const double at = t0 + (double(j) + 0.5) * period;
    while (k + 1 < ticks.size() && ticks[k + 1].t <= at) {
      ++k;
      if (finite(ticks[k].force)) held = ticks[k].force;
    }
    f[0].push_back(held.x);
    f[1].push_back(held.y);
    f[2].push_back(held.z);
  }
  return f;
}

}  // namespace

ForceSpectrum force_spectrum(const Recording& r, double cutoff_hz, double band_hz, double segment_s) {
  ForceSpectrum s;
  s.cutoff_hz = cutoff_hz;
  if (r.haptic.size() < 2) return s;
  const double rate = sampling_rate(r);
  const double nyquist = rate / 2;
  if (!(rate > 0) || !(cutoff_hz > 0) || !(band_hz > 0) || cutoff_hz >= nyquist) return s;
  const std::array<std::vector<double>, 3> f = held_force(r.haptic, rate);
  const std::size_t n = f[0].size();
  if (n < kMinTicks) return s;

  // The fluctuation: the force minus its mean over the whole recording.
  double fluctuation_ms = 0;
  for (const std::vector<double>& axis : f) {
    double mean = 0;
    for (double x : axis) mean += x;
    mean /= double(n);
    for (double x : axis) fluctuation_ms += (x - mean) * (x - mean);
  }
  fluctuation_ms /= double(n);

  // Welch: Hann segments of `len` samples overlapping by half, the last one ending at the end.
  const std::size_t len =
      std::clamp(std::size_t(std::llround(std::max(0.0, segment_s) * rate)), kMinTicks, n);
  std::vector<std::size_t> starts;
  for (std::size_t b = 0; b + len <= n; b += len / 2) starts.push_back(b);
  if (starts.back() + len < n) starts.push_back(n - len);
  std::vector<double> window(len);
  double window_ss = 0;
  for (std::size_t i = 0; i < len; ++i) {
    window[i] = 0.5 * (1 - std::cos(2 * std::numbers::pi * double(i) / double(len)));
    window_ss += window[i] * window[i];
  }
  const std::size_t bins = len / 2 + 1;
  std::vector<double> power(bins, 0.0);  // mean square of the force per bin, one-sided, axes summed
  RealFft fft(len);
  for (std::size_t b : starts) {
    for (const std::vector<double>& axis : f) {
      double mean = 0;
      for (std::size_t i = 0; i < len; ++i) mean += axis[b + i];
      mean /= double(len);
      for (std::size_t i = 0; i < len; ++i) fft.in()[i] = (axis[b + i] - mean) * window[i];
      const std::vector<std::complex<double>>& spectrum = fft.run();
      for (std::size_t k = 0; k < bins; ++k) {
        const double one_sided = (k == 0 || 2 * k == len) ? 1 : 2;
        power[k] += one_sided * std::norm(spectrum[k]) / (double(len) * window_ss);
      }
    }
  }
  for (double& p : power) p /= double(starts.size());

  // Below 1e-10 of the largest force component is the rounding of the means removed, not force:
  // a constant force has no fluctuation and nothing above the cutoff.
  double largest = 0;
  for (const std::vector<double>& axis : f)
    for (double x : axis) largest = std::max(largest, std::abs(x));
  const double rounding_ms = 1e-20 * largest * largest;
  if (fluctuation_ms <= rounding_ms) fluctuation_ms = 0;
  double total_ms = 0;
  for (double p : power) total_ms += p;
  if (total_ms <= rounding_ms) std::fill(power.begin(), power.end(), 0.0);

  const double bin_hz = rate / double(len);
  const auto band_count = std::size_t(std::ceil((nyquist - cutoff_hz) / band_hz));
  std::vector<double> band_ms(band_count, 0.0);
  double above_ms = 0;
  std::size_t peak = 0;
  for (std::size_t k = 0; k < bins; ++k) {
    const double at = double(k) * bin_hz;
    if (at < cutoff_hz) continue;
    above_ms += power[k];
    band_ms[std::min(band_count - 1, std::size_t((at - cutoff_hz) / band_hz))] += power[k];
    if (peak == 0 || power[k] > power[peak]) peak = k;
  }

  s.rate_hz = rate;
  s.ticks = n;
  s.segment_s = double(len) / rate;
  s.segments = starts.size();
  s.fluctuation_rms_N = std::sqrt(fluctuation_ms);
  s.above_rms_N = std::sqrt(above_ms);
  // Welch's estimate of the power above the cutoff can exceed the whole fluctuation's by a little
  // (a signal all above the cutoff): the share is at most 1.
  s.above_share = fluctuation_ms > 0 ? std::min(1.0, s.above_rms_N / s.fluctuation_rms_N) : 0;
  if (peak > 0 && power[peak] > 0) {
    double lobe = 0;  // a Hann window spreads a sine over at most 4 bins
    for (std::size_t k = peak >= 2 ? peak - 2 : 0; k <= std::min(bins - 1, peak + 2); ++k) lobe += power[k];
    s.peak_hz = double(peak) * bin_hz;
    s.peak_amplitude_N = std::sqrt(2 * lobe);
  }
  for (std::size_t b = 0; b < band_count; ++b) {
    const double lo = cutoff_hz + double(b) * band_hz;
    s.bands.push_back({lo, std::min(nyquist, lo + band_hz), std::sqrt(band_ms[b])});
    if (band_ms[b] > band_ms[s.top_band]) s.top_band = b;
  }
  return s;
}

}  // namespace dentsph

// The realtime run's sections of summary.json and its report for a person.
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "dentsph/haptics.hpp"
#include "dentsph/limits.hpp"

namespace dentsph {

namespace {

nlohmann::json spectrum_json(const ForceSpectrum& s) {
  nlohmann::json bands = nlohmann::json::array();
  for (const ForceBand& b : s.bands) bands.push_back({{"lo_hz", b.lo_hz}, {"hi_hz", b.hi_hz}, {"rms_N", b.rms_N}});
  nlohmann::json top = nullptr;
  if (s.above_rms_N > 0 && !s.bands.empty()) {
    const ForceBand& b = s.bands[s.top_band];
    top = {{"lo_hz", b.lo_hz}, {"hi_hz", b.hi_hz}, {"rms_N", b.rms_N}};
  }
  return {{"cutoff_hz", s.cutoff_hz},
          {"rate_hz", s.rate_hz},
          {"ticks", s.ticks},
          {"segment_s", s.segment_s},
          {"segments", s.segments},
          {"fluctuation_rms_N", s.fluctuation_rms_N},
          {"above_rms_N", s.above_rms_N},
          {"above_share", s.above_share},
          {"peak_hz", s.peak_hz},
          {"peak_amplitude_N", s.peak_amplitude_N},
          {"top_band", top},
          {"bands", bands}};
}

// The printed line of the force's spectrum.
std::string spectrum_line(const ForceSpectrum& s) {
  if (s.ticks == 0) return fmt::format("force above {:.0f} Hz: not measured (recording too short)\n", s.cutoff_hz);
  std::string line = fmt::format("force above {:.0f} Hz: rms {:.3g} N, {:.1f}% of the force's fluctuation (rms {:.3g} N)",
                                 s.cutoff_hz, s.above_rms_N, 100 * s.above_share, s.fluctuation_rms_N);
  if (s.peak_hz > 0) {
    const ForceBand& b = s.bands[s.top_band];
    line += fmt::format("; most in {:.0f}-{:.0f} Hz (rms {:.3g} N), peak {:.0f} Hz ({:.3g} N amplitude)", b.lo_hz,
                        b.hi_hz, b.rms_N, s.peak_hz, s.peak_amplitude_N);
  }
  return line + fmt::format("; {} ticks held at {:.0f} Hz, {:.2g} s Hann segments\n", s.ticks, s.rate_hz, s.segment_s);
}

}  // namespace

std::string realtime_json(const RealtimeResult& r) {
  const HapticReport& h = r.haptic;
  nlohmann::json j;
  j["haptic"] = {{"target_rate_hz", h.target_rate_hz},
                 {"rate_hz", h.timing.rate_hz},
                 {"realtime_priority", h.realtime_priority},
                 {"ticks", h.timing.ticks},
                 {"period_p50_us", h.timing.period_p50_us},
                 {"period_p99_us", h.timing.period_p99_us},
                 {"period_max_us", h.timing.period_max_us},
                 {"deadline_misses", h.timing.deadline_misses},
                 {"force_age_p50_us", h.force_age_p50_us},
                 {"force_age_p99_us", h.force_age_p99_us},
                 {"force_age_max_us", h.force_age_max_us},
                 {"max_force_N", h.max_force_N},
                 {"max_force_step_N", h.max_force_step_N},
                 {"profile", {{"name", h.profile.name},
                              {"max_force_N", h.profile.max_force_N},
                              {"max_force_rate_N_per_s", h.profile.max_force_rate_N_per_s},
                              {"max_torque_N_m", h.profile.max_torque_N_m},
                              {"contact_stiffness_N_per_m", h.profile.contact.stiffness_N_per_m},
                              {"contact_damping_N_s_per_m", h.profile.contact.damping_N_s_per_m},
                              {"contact_friction", h.profile.contact.friction}}},
                 {"hard_contact", {{"ticks", h.contact_ticks},
                                   {"rebuilds", h.contact_rebuilds},
                                   {"build_max_ms", h.contact_build_max_ms}}},
                 {"mode", r.recording.mode},
                 {"force_scale", r.recording.force_scale},
                 {"limits", {{"magnitude_limited_ticks", h.magnitude_limited_ticks},
                             {"rate_limited_ticks", h.rate_limited_ticks},
                             {"non_finite_rejected", h.non_finite_rejected},
                             {"non_finite_poses", h.non_finite_poses}}},
                 {"passivity", {{"damped_ticks", h.passivity_damped_ticks}, {"energy_J", h.passivity_energy_J}}},
                 {"sessions", h.sessions},
                 {"dispense_presses", h.dispense_presses},
                 {"dispense_presses_refused", h.dispense_presses_refused},
                 {"light_presses", h.light_presses},
                 {"light_presses_refused", h.light_presses_refused},
                 {"watchdog", {{"trips", h.watchdog_trips},
                               {"sim_stale_ticks", h.sim_stale_ticks},
                               {"pose_stale_ticks", h.pose_stale_ticks},
                               {"zero_gain_ticks", h.zero_gain_ticks}}},
                 {"free_air", {{"window_s", h.free_air.window_s},
                               {"free_ticks", h.free_air.free_ticks},
                               {"free_mean_N", h.free_air.free_mean_N},
                               {"free_p95_N", h.free_air.free_p95_N},
                               {"contact_ticks", h.free_air.contact_ticks},
                               {"contact_mean_N", h.free_air.contact_mean_N},
                               {"contact_p95_N", h.free_air.contact_p95_N}}},
                 {"spectrum", spectrum_json(h.force_spectrum)},
                 {"recorded_ticks", r.recording.haptic.size()},
                 {"recording_dropped_ticks", r.recording.haptic_dropped}};
  j["sim"] = {{"backend", r.run.backend},
              {"steps", r.sim.steps},
              {"steps_per_second", r.sim.steps_per_second},
              {"realtime_factor", r.sim.realtime_factor},
              {"step_p50_us", r.sim.step_p50_us},
              {"step_p99_us", r.sim.step_p99_us},
              {"step_max_us", r.sim.step_max_us},
              {"stalls_injected", r.sim.stalls_injected},
              {"button_dispenses", r.sim.button_dispenses},
              {"light_toggles", r.sim.light_toggles}};
  j["consumer"] = {{"frames", r.consumer.frames},
                   {"rate_hz", r.consumer.rate_hz},
                   {"snapshot_age_p99_us", r.consumer.snapshot_age_p99_us}};
  nlohmann::json dev = nlohmann::json::parse(r.device_json.empty() ? "{}" : r.device_json);
  dev["name"] = r.device_name;
  j["device"] = dev;
  return j.dump();
}

std::string realtime_report(const RealtimeResult& r) {
  const HapticReport& h = r.haptic;
  return fmt::format(
      "haptic loop ({} mode, {} device): {:.1f} Hz of {:.0f} Hz, period p50 {:.0f} us, p99 {:.0f} us, max {:.0f} us, "
      "{} deadline misses in {} ticks\n"
      "force: age p50 {:.0f} us, p99 {:.0f} us; largest {:.4g} N, largest step {:.4g} N; limited {} (magnitude) / {} "
      "(rate) ticks; watchdog trips {}, ticks at zero gain {}\n"
      "force in air (no tool force for {:.0f} ms, no hard contact): mean {:.3f} N, p95 {:.3f} N over {} ticks; in contact: mean {:.3f} N, "
      "p95 {:.3f} N over {} ticks\n"
      "hard contact (tooth, band, set paste; {:.0f} N/m, friction {:.2f}): {} ticks touching, field rebuilt {} times "
      "(longest {:.1f} ms)\n"
      "{}"
      "simulation ({}): {} steps, {:.0f} steps/s ({:.3f} x real time), step p50 {:.0f} us, p99 {:.0f} us; {} increments "
      "dispensed by the button ({} presses over {} a second refused), the light toggled {} times ({} presses "
      "refused)\n"
      "consumer: {} snapshots at {:.1f} Hz\n",
      r.recording.mode, r.device_name, h.timing.rate_hz, h.target_rate_hz, h.timing.period_p50_us,
      h.timing.period_p99_us, h.timing.period_max_us, h.timing.deadline_misses, h.timing.ticks, h.force_age_p50_us,
      h.force_age_p99_us, h.max_force_N, h.max_force_step_N, h.magnitude_limited_ticks, h.rate_limited_ticks,
      h.watchdog_trips, h.zero_gain_ticks, h.free_air.window_s * 1e3, h.free_air.free_mean_N, h.free_air.free_p95_N,
      h.free_air.free_ticks, h.free_air.contact_mean_N, h.free_air.contact_p95_N, h.free_air.contact_ticks,
      h.profile.contact.stiffness_N_per_m, h.profile.contact.friction, h.contact_ticks, h.contact_rebuilds,
      h.contact_build_max_ms, spectrum_line(h.force_spectrum), r.run.backend, r.sim.steps, r.sim.steps_per_second, r.sim.realtime_factor,
      r.sim.step_p50_us, r.sim.step_p99_us, r.sim.button_dispenses, h.dispense_presses_refused,
      limits::max_dispense_presses_per_s, r.sim.light_toggles, h.light_presses_refused, r.consumer.frames,
      r.consumer.rate_hz);
}

}  // namespace dentsph

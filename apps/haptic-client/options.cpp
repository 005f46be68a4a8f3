// The reference client's options (options.hpp).
#include "options.hpp"

#include <cmath>
#include <numbers>

#include <CLI/CLI.hpp>

#include "option_checks.hpp"

namespace dentsph::haptic_client {

using cli::finite_positive;
using cli::finite_range;

void add_options(CLI::App& app, Options& o) {
  app.add_option("--host", o.host, "dentsph's IPv4 address")->capture_default_str();
  app.add_option("--port", o.port, "dentsph's UDP port")->capture_default_str();
  app.add_option("--rate", o.rate_hz, "Poses per second")->check(finite_range(1.0, 10000.0))->capture_default_str();
  app.add_option("--duration", o.duration_s, "Seconds to run")->check(finite_positive(86400))->capture_default_str();
  app.add_option("--motion", o.motion, "press (down and up), hold (down and stay), circle, still")
      ->check(CLI::IsMember({"press", "hold", "circle", "still"}))
      ->capture_default_str();
  app.add_option("--depth", o.depth_m, "Depth of the motion (m, device frame)")->check(finite_range(-1, 1))->capture_default_str();
  app.add_option("--period", o.period_s, "Period of the motion (s)")->check(finite_positive(3600))->capture_default_str();
  app.add_option("--axis", o.axis, "Direction of press and hold (device frame, any length)")
      ->expected(3)
      ->each([](const std::string& v) {
        if (!std::isfinite(std::stod(v))) throw CLI::ValidationError("--axis", "not a finite number: " + v);
      })
      ->capture_default_str();
  app.add_option("--orientation", o.orientation, "The instrument's orientation, a quaternion w x y z (any length)")
      ->expected(4)
      ->each([](const std::string& v) {
        if (!std::isfinite(std::stod(v))) throw CLI::ValidationError("--orientation", "not a finite number: " + v);
      })
      ->capture_default_str();
  app.add_option("--limit", o.limit_N, "The device's force limit (N): larger forces are reported")
      ->check(finite_positive(1000))
      ->capture_default_str();
  app.add_flag("--torque", o.torque, "Play a device that renders torque: ask for wrench packets (force and torque)");
  app.add_option("--torque-limit", o.torque_limit_N_m, "The device's torque limit (N m): larger torques are reported")
      ->check(finite_positive(1000))
      ->capture_default_str();
  app.add_option("--drop", o.drop, "Probability that a pose is not sent")->check(finite_range(0.0, 1.0));
  app.add_option("--duplicate", o.duplicate, "Probability that a pose is sent twice")->check(finite_range(0.0, 1.0));
  app.add_option("--reorder", o.reorder, "Probability that a pose is sent after the next one")->check(finite_range(0.0, 1.0));
  app.add_option("--truncate", o.truncate, "Probability that a pose is cut short")->check(finite_range(0.0, 1.0));
  app.add_option("--garbage", o.garbage, "Probability of a random datagram after a pose")->check(finite_range(0.0, 1.0));
  app.add_option("--pause-at", o.pause_at_s, "Go silent at this time (s)")->check(finite_range(-1, 86400));
  app.add_option("--pause-for", o.pause_for_s, "For this long (s)")->check(finite_range(0.0, 86400.0));
  app.add_option("--press-button-at", o.press_button_at_s,
                 "Hold button 1 (dispense an increment) down from these times (s), e.g. --press-button-at 0.5 1.5");
  app.add_option("--press-button-for", o.press_button_for_s, "For this long each time (s)")
      ->check(finite_positive(3600))
      ->capture_default_str();
  app.add_flag("!--no-bye", o.bye, "Leave without saying bye");
  app.add_flag("--hello", o.hello, "Say hello before the first pose (and at --restart-at): a new session");
  app.add_option("--restart-at", o.restart_at_s, "Number the poses from 1 again at this time (s), as a restarted client")
      ->check(finite_range(-1, 86400));
  app.add_option("--heartbeat-every", o.heartbeat_every_s, "Send a heartbeat this often (s) between poses")
      ->check(finite_range(0, 3600));
  app.add_option("--scale", o.scale, "Send positions times this (1000: a client that sends millimetres)")
      ->check(finite_range(1e-6, 1e6))
      ->capture_default_str();
  app.add_option("--spike-at", o.spike_at_s, "Send one absurd pose at this time (s)...")->check(finite_range(-1, 86400));
  app.add_option("--spike-m", o.spike_m, "... with x this many metres");
  app.add_option("--toggle-button-hz", o.toggle_button_hz, "Toggle button 1 at this rate (Hz) the whole run")
      ->check(finite_range(0, 10000));
  app.add_option("--toggle-light-hz", o.toggle_light_hz, "Toggle button 2 (the curing light) at this rate (Hz) the whole run")
      ->check(finite_range(0, 10000));
  app.add_option("--start-after", o.start_after_s, "Wait this long (s) before the first message")
      ->check(finite_range(0.0, 86400.0));
  app.add_option("--wait", o.wait_s,
                 "Send a heartbeat every 100 ms until dentsph answers, at most this long (s), before the first pose "
                 "(a dentsph still starting misses no pose); exit 3 if it never answers")
      ->check(finite_range(0.0, 86400.0));
  app.add_option("--seed", o.seed, "Seed of the fault injection")->capture_default_str();
  app.add_option("--report", o.report, "Write what the client saw as JSON to this file");
}

std::string check_options(Options& o) {
  if (!(std::hypot(o.axis[0], o.axis[1], o.axis[2]) > 0)) return "--axis must not be zero";
  const double q_norm = std::sqrt(o.orientation[0] * o.orientation[0] + o.orientation[1] * o.orientation[1] +
                                  o.orientation[2] * o.orientation[2] + o.orientation[3] * o.orientation[3]);
  if (!(q_norm > 0)) return "--orientation must not be zero";
  for (double& v : o.orientation) v /= q_norm;
  return {};
}

std::array<double, 3> motion(const Options& o, double t) {
  const double w = 2 * std::numbers::pi / o.period_s;
  const double n = std::hypot(o.axis[0], o.axis[1], o.axis[2]);
  auto along = [&](double d) { return std::array<double, 3>{o.axis[0] * d / n, o.axis[1] * d / n, o.axis[2] * d / n}; };
  if (o.motion == "press") return along(o.depth_m * 0.5 * (1 - std::cos(w * t)));
  if (o.motion == "hold") {
    const double s = std::min(1.0, t / (0.3 * o.period_s));
    return along(o.depth_m * s * s * (3 - 2 * s));
  }
  if (o.motion == "circle") return {0.5 * o.depth_m * std::cos(w * t), 0.5 * o.depth_m * std::sin(w * t), -o.depth_m};
  return {0, 0, 0};
}

}  // namespace dentsph::haptic_client

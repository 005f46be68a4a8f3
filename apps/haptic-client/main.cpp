// dentsph-haptic-client: the reference client of the haptic bridge (docs/haptic-protocol.md).
// It plays a haptic device: at a fixed rate it sends a pose (a scripted motion in the device
// frame), and reads the forces dentsph sends back, checking each one (finite, within the limit,
// answering a pose it sent). A program written with a haptic SDK does the same with the device's
// pose and renders the force. It numbers its poses as the protocol says (+1 per pose; its hello,
// heartbeats and bye carry the newest pose's number). Faults can be injected (dropped,
// duplicated, reordered, truncated and garbage packets, a silence, a restart of its numbering,
// an absurd pose, positions in the wrong units, a button toggled too fast) to exercise the
// runtime; --report writes what it saw as JSON.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <pthread.h>
#include <sched.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <numbers>
#include <random>
#include <span>
#include <thread>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "dentsph/haptics/protocol.hpp"
#include "option_checks.hpp"

namespace proto = dentsph::haptic_protocol;
using dentsph::cli::finite_positive;
using dentsph::cli::finite_range;

namespace {

using Clock = std::chrono::steady_clock;

std::uint64_t now_ns() {
  return std::uint64_t(std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now().time_since_epoch()).count());
}

struct Options {
  std::string host = "127.0.0.1";
  std::uint16_t port = 47000;
  double rate_hz = 1000, duration_s = 3;
  std::string motion = "press";  // press | hold | circle | still
  double depth_m = 0.03, period_s = 1.0;
  std::vector<double> axis{0, 0, -1};  // direction of press and hold (normalised)
  std::vector<double> orientation{1, 0, 0, 0};  // the instrument's, a quaternion w x y z (normalised)
  double limit_N = 9.0;
  bool torque = false;             // a 6-DoF device: ask for wrench packets (kCapabilityTorque)
  double torque_limit_N_m = 0.4;
  double drop = 0, duplicate = 0, reorder = 0, truncate = 0, garbage = 0;
  double pause_at_s = -1, pause_for_s = 0;
  std::vector<double> press_button_at_s;  // button 1 (dispense) down for press_button_for_s from each
  double press_button_for_s = 0.1;
  bool bye = true, hello = false;
  double restart_at_s = -1;        // number the poses from 1 again (same socket), as a restarted client
  double heartbeat_every_s = 0;    // heartbeats between poses
  double scale = 1;                // positions sent times this (1000: a client sending millimetres)
  double spike_at_s = -1, spike_m = 0;  // one pose at this time with x = spike_m
  double toggle_button_hz = 0;     // button 1 toggled at this rate the whole run
  double toggle_light_hz = 0;      // button 2 (the curing light) toggled at this rate the whole run
  double start_after_s = 0;        // wait this long before the first message
  double wait_s = 0;               // > 0: heartbeats until dentsph answers, at most this long, before the first pose
  unsigned seed = 1;
  std::string report;
};

// The device's position at time t (m, device frame): the motion a hand would make.
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

struct Stats {
  std::uint64_t poses_sent = 0, dropped = 0, duplicated = 0, reordered = 0, truncated = 0, garbage = 0;
  std::uint64_t forces = 0, heartbeats = 0, malformed = 0, non_finite = 0, over_limit = 0;
  std::uint64_t wrenches = 0, torque_over_limit = 0;
  double max_torque_N_m = 0;
  std::array<double, 3> last_force{}, last_torque{};
  std::uint64_t ack_ahead = 0, ack_backwards = 0, echo_mismatch = 0;
  double max_force_N = 0;
  std::vector<double> lags, rtts_us;
};

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, std::size_t(q * double(v.size())))];
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  CLI::App app{"dentsph-haptic-client: plays a haptic device over UDP against `dentsph run --realtime --device udp`"};
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
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;  // a refused command line exits 2, as every refusal (CLI11's codes are 100 and up)
  }

  if (!(std::hypot(o.axis[0], o.axis[1], o.axis[2]) > 0)) {
    fmt::print(stderr, "error: --axis must not be zero\n");
    return 2;
  }
  const double q_norm = std::sqrt(o.orientation[0] * o.orientation[0] + o.orientation[1] * o.orientation[1] +
                                  o.orientation[2] * o.orientation[2] + o.orientation[3] * o.orientation[3]);
  if (!(q_norm > 0)) {
    fmt::print(stderr, "error: --orientation must not be zero\n");
    return 2;
  }
  for (double& v : o.orientation) v /= q_norm;

  // Like a device SDK's servo thread: real-time priority where allowed (root or CAP_SYS_NICE).
  sched_param sp{};
  sp.sched_priority = 20;
  pthread_setschedparam(pthread_self(), SCHED_FIFO, &sp);

  const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(o.port);
  if (fd < 0 || ::inet_pton(AF_INET, o.host.c_str(), &to.sin_addr) != 1) {
    fmt::print(stderr, "error: cannot use {}:{} (an IPv4 address is needed)\n", o.host, o.port);
    return 2;
  }
  auto send = [&](std::span<const std::uint8_t> b) {
    ::sendto(fd, b.data(), b.size(), 0, reinterpret_cast<const sockaddr*>(&to), sizeof to);
  };

  std::mt19937 rng(o.seed);
  std::uniform_real_distribution<double> u(0, 1);
  Stats st;
  std::this_thread::sleep_for(std::chrono::duration<double>(o.start_after_s));
  std::vector<std::uint64_t> sent_stamp(1 << 16, 0);  // timestamp of each sequence (mod 65536)
  std::uint32_t seq = 0, last_ack = 0;
  bool have_ack = false, restarted = false;
  std::uint64_t forces_after_restart = 0;
  std::vector<std::uint8_t> held;  // a pose held back to be sent after the next one
  std::array<std::uint8_t, proto::kMaxPacketBytes> buf{};
  std::array<std::uint8_t, 2048> in{};

  auto receive = [&] {
    while (true) {
      const ssize_t n = ::recv(fd, in.data(), in.size(), MSG_DONTWAIT);
      if (n < 0) return;
      const std::uint64_t t = now_ns();
      proto::Header h;
      const std::span<const std::uint8_t> d(in.data(), std::size_t(n));
      if (proto::decode_header(d, h) != proto::DecodeError::none) {
        ++st.malformed;
        continue;
      }
      if (h.type == proto::Type::heartbeat) {
        ++st.heartbeats;
        continue;
      }
      proto::ForcePacket f;
      const proto::DecodeError e = proto::decode(d, f);
      if (e == proto::DecodeError::non_finite) {
        ++st.non_finite;
        ++st.forces;
        continue;
      }
      if (e != proto::DecodeError::none) {
        ++st.malformed;
        continue;
      }
      ++st.forces;
      if (restarted) {
        if (proto::sequence_newer(f.pose_sequence, seq)) continue;  // answers a pose of the session before
        ++forces_after_restart;
      }
      // |f| as dentsph's limiter computes it (the root of the sum of squares: std::hypot rounds
      // otherwise, and a force limited to exactly 9 N read 9.000000000000002).
      const double mag = std::sqrt(f.force[0] * f.force[0] + f.force[1] * f.force[1] + f.force[2] * f.force[2]);
      st.max_force_N = std::max(st.max_force_N, mag);
      if (mag > o.limit_N) ++st.over_limit;
      if (h.type == proto::Type::wrench) {
        ++st.wrenches;
        const double tau = std::sqrt(f.torque[0] * f.torque[0] + f.torque[1] * f.torque[1] + f.torque[2] * f.torque[2]);
        st.max_torque_N_m = std::max(st.max_torque_N_m, tau);
        if (tau > o.torque_limit_N_m) ++st.torque_over_limit;
      }
      std::copy(std::begin(f.force), std::end(f.force), st.last_force.begin());
      std::copy(std::begin(f.torque), std::end(f.torque), st.last_torque.begin());
      // The force answers a pose: one we sent (not ahead of us), never an older one than before.
      if (proto::sequence_newer(f.pose_sequence, seq)) ++st.ack_ahead;
      if (have_ack && proto::sequence_newer(last_ack, f.pose_sequence)) ++st.ack_backwards;
      if (sent_stamp[f.pose_sequence & 0xffff] != f.pose_timestamp_ns) ++st.echo_mismatch;
      st.lags.push_back(double(seq - f.pose_sequence));
      st.rtts_us.push_back(double(t - f.pose_timestamp_ns) * 1e-3);
      last_ack = f.pose_sequence;
      have_ack = true;
    }
  };

  // hello, heartbeat and bye: the header alone, carrying the newest pose's number (docs/haptic-protocol.md).
  auto send_header = [&](proto::Type type) {
    proto::Header h;
    h.type = type;
    h.sequence = seq;
    h.timestamp_ns = now_ns();
    send(std::span<const std::uint8_t>(buf.data(), proto::encode_header_only(h, buf)));
  };
  std::uint64_t hellos = 0, heartbeats_sent = 0, restarts = 0, spikes = 0;
  if (o.wait_s > 0) {
    // The first valid message opens a session (a heartbeat: a hello would open a new one each
    // time), and dentsph sends a heartbeat every 100 ms while a session has no pose
    // (docs/haptic-protocol.md): the first message back says it listens.
    const auto until = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(o.wait_s));
    auto heard = [&] { return st.heartbeats + st.forces + st.malformed; };  // every message receive() counts
    const std::uint64_t before = heard();
    while (heard() == before && Clock::now() < until) {
      send_header(proto::Type::heartbeat);
      ++heartbeats_sent;
      const auto next_beat = Clock::now() + std::chrono::milliseconds(100);
      while (heard() == before && Clock::now() < next_beat) {
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
        receive();
      }
    }
    const bool answered = heard() > before;
    if (!answered) {
      fmt::print(stderr, "error: dentsph at {}:{} did not answer within {} s (--wait); is it running with --device udp?\n",
                 o.host, o.port, o.wait_s);
      ::close(fd);
      return 3;
    }
  }
  if (o.hello) send_header(proto::Type::hello), ++hellos;

  const auto period = std::chrono::nanoseconds(std::int64_t(1e9 / o.rate_hz));
  const auto start = Clock::now();
  auto next = start;
  bool paused_done = false, spiked = false;
  double next_heartbeat = o.heartbeat_every_s;
  for (;;) {
    std::this_thread::sleep_until(next);
    next += period;
    const double t = std::chrono::duration<double>(Clock::now() - start).count();
    if (t >= o.duration_s) break;
    receive();
    if (o.pause_at_s >= 0 && !paused_done && t >= o.pause_at_s) {
      if (!held.empty()) send(held), held.clear();
      std::this_thread::sleep_for(std::chrono::duration<double>(o.pause_for_s));
      paused_done = true;
      next = Clock::now();
      continue;
    }
    if (o.restart_at_s >= 0 && !restarted && t >= o.restart_at_s) {
      restarted = true;
      ++restarts;
      seq = 0;
      have_ack = false;
      if (o.hello) send_header(proto::Type::hello), ++hellos;
    }
    if (o.heartbeat_every_s > 0 && t >= next_heartbeat) {
      send_header(proto::Type::heartbeat);
      ++heartbeats_sent;
      next_heartbeat += o.heartbeat_every_s;
    }
    proto::PosePacket p;
    p.header.sequence = ++seq;
    p.header.timestamp_ns = now_ns();
    if (o.torque) p.capabilities = proto::kCapabilityTorque;
    for (int a = 0; a < 4; ++a) p.orientation[a] = o.orientation[std::size_t(a)];
    sent_stamp[seq & 0xffff] = p.header.timestamp_ns;
    const auto x = motion(o, t);
    for (int a = 0; a < 3; ++a) p.position[a] = o.scale * x[std::size_t(a)];
    if (o.spike_at_s >= 0 && !spiked && t >= o.spike_at_s) {
      spiked = true;
      ++spikes;
      p.position[0] = o.spike_m;
    }
    for (const double at : o.press_button_at_s)
      if (t >= at && t < at + o.press_button_for_s) p.buttons |= proto::kButtonDispense;
    if (o.toggle_button_hz > 0 && std::fmod(t * o.toggle_button_hz, 1.0) < 0.5) p.buttons |= proto::kButtonDispense;
    if (o.toggle_light_hz > 0 && std::fmod(t * o.toggle_light_hz, 1.0) < 0.5) p.buttons |= proto::kButtonLight;
    const std::size_t n = proto::encode(p, buf);
    ++st.poses_sent;
    const std::span<const std::uint8_t> pkt(buf.data(), n);
    // One fault at most per pose, none on the pose that releases a held one, none in the last
    // 50 ms (so that every skipped pose is followed by one that reveals the gap).
    const double r = t < o.duration_s - 0.05 ? u(rng) : 1.0;
    double c = 0;
    if (!held.empty()) {
      send(pkt);
      send(held);
      held.clear();
    } else if (r < (c += o.drop)) {
      ++st.dropped;
    } else if (r < (c += o.duplicate)) {
      send(pkt), send(pkt);
      ++st.duplicated;
    } else if (r < (c += o.reorder)) {
      held.assign(pkt.begin(), pkt.end());
      ++st.reordered;
    } else if (r < (c += o.truncate)) {
      send(pkt.first(std::size_t(u(rng) * double(n - 1))));
      ++st.truncated;
    } else {
      send(pkt);
    }
    if (u(rng) < o.garbage && t < o.duration_s - 0.05) {
      std::vector<std::uint8_t> g(1 + std::size_t(u(rng) * 200));
      for (auto& b : g) b = std::uint8_t(rng());
      send(g);
      ++st.garbage;
    }
  }
  if (!held.empty()) send(held);
  const auto drain_until = Clock::now() + std::chrono::milliseconds(20);
  while (Clock::now() < drain_until) {
    receive();
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  if (o.bye) send_header(proto::Type::bye);
  ::close(fd);

  nlohmann::json j = {{"poses_sent", st.poses_sent},     {"dropped", st.dropped},
                      {"duplicated", st.duplicated},     {"reordered", st.reordered},
                      {"truncated", st.truncated},       {"garbage", st.garbage},
                      {"forces_received", st.forces},    {"heartbeats_received", st.heartbeats},
                      {"malformed_received", st.malformed}, {"non_finite_forces", st.non_finite},
                      {"forces_over_limit", st.over_limit}, {"max_force_N", st.max_force_N},
                      {"acks_ahead", st.ack_ahead},      {"acks_backwards", st.ack_backwards},
                      {"echo_mismatches", st.echo_mismatch},
                      {"ack_lag_p50", quantile(st.lags, 0.5)}, {"ack_lag_p99", quantile(st.lags, 0.99)},
                      {"ack_lag_max", st.lags.empty() ? 0.0 : *std::max_element(st.lags.begin(), st.lags.end())},
                      {"rtt_p50_us", quantile(st.rtts_us, 0.5)}, {"rtt_p99_us", quantile(st.rtts_us, 0.99)},
                      {"hellos_sent", hellos}, {"heartbeats_sent", heartbeats_sent}, {"restarts", restarts},
                      {"spikes", spikes}, {"forces_after_restart", forces_after_restart},
                      {"wrenches_received", st.wrenches}, {"max_torque_N_m", st.max_torque_N_m},
                      {"torques_over_limit", st.torque_over_limit}, {"last_force_N", st.last_force},
                      {"last_torque_N_m", st.last_torque}};
  if (o.report.empty())
    fmt::print("{}\n", j.dump(2));
  else
    std::ofstream(o.report) << j.dump(2) << "\n";
  return 0;
}

// The reference client's device (client.hpp).
#include "client.hpp"

#include <arpa/inet.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <thread>

#include <fmt/format.h>

namespace dentsph::haptic_client {

namespace {

using Clock = std::chrono::steady_clock;

std::uint64_t now_ns() {
  return std::uint64_t(std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now().time_since_epoch()).count());
}

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, std::size_t(q * double(v.size())))];
}

}  // namespace

Client::Client(const Options& o) : o_(o), rng_(o.seed) {
  fd_ = ::socket(AF_INET, SOCK_DGRAM, 0);
  to_.sin_family = AF_INET;
  to_.sin_port = htons(o.port);
  if (fd_ < 0 || ::inet_pton(AF_INET, o.host.c_str(), &to_.sin_addr) != 1) {
    if (fd_ >= 0) ::close(fd_);
    throw std::invalid_argument(fmt::format("cannot use {}:{} (an IPv4 address is needed)", o.host, o.port));
  }
}

Client::~Client() { ::close(fd_); }

void Client::send(std::span<const std::uint8_t> b) {
  ::sendto(fd_, b.data(), b.size(), 0, reinterpret_cast<const sockaddr*>(&to_), sizeof to_);
}

void Client::send_header(proto::Type type) {
  proto::Header h;
  h.type = type;
  h.sequence = seq_;
  h.timestamp_ns = now_ns();
  send(std::span<const std::uint8_t>(buf_.data(), proto::encode_header_only(h, buf_)));
}

void Client::receive() {
  while (true) {
    const ssize_t n = ::recv(fd_, in_.data(), in_.size(), MSG_DONTWAIT);
    if (n < 0) return;
    const std::uint64_t t = now_ns();
    proto::Header h;
    const std::span<const std::uint8_t> d(in_.data(), std::size_t(n));
    if (proto::decode_header(d, h) != proto::DecodeError::none) {
      ++st_.malformed;
      continue;
    }
    if (h.type == proto::Type::heartbeat) {
      ++st_.heartbeats;
      continue;
    }
    proto::ForcePacket f;
    const proto::DecodeError e = proto::decode(d, f);
    if (e == proto::DecodeError::non_finite) {
      ++st_.non_finite;
      ++st_.forces;
      continue;
    }
    if (e != proto::DecodeError::none) {
      ++st_.malformed;
      continue;
    }
    ++st_.forces;
    if (restarted_) {
      if (proto::sequence_newer(f.pose_sequence, seq_)) continue;  // answers a pose of the session before
      ++forces_after_restart_;
    }
    // |f| as dentsph's limiter computes it (the root of the sum of squares: std::hypot rounds
    // otherwise, and a force limited to exactly 9 N read 9.000000000000002).
    const double mag = std::sqrt(f.force[0] * f.force[0] + f.force[1] * f.force[1] + f.force[2] * f.force[2]);
    st_.max_force_N = std::max(st_.max_force_N, mag);
    if (mag > o_.limit_N) ++st_.over_limit;
    if (h.type == proto::Type::wrench) {
      ++st_.wrenches;
      const double tau = std::sqrt(f.torque[0] * f.torque[0] + f.torque[1] * f.torque[1] + f.torque[2] * f.torque[2]);
      st_.max_torque_N_m = std::max(st_.max_torque_N_m, tau);
      if (tau > o_.torque_limit_N_m) ++st_.torque_over_limit;
    }
    std::copy(std::begin(f.force), std::end(f.force), st_.last_force.begin());
    std::copy(std::begin(f.torque), std::end(f.torque), st_.last_torque.begin());
    // The force answers a pose: one we sent (not ahead of us), never an older one than before.
    if (proto::sequence_newer(f.pose_sequence, seq_)) ++st_.ack_ahead;
    if (have_ack_ && proto::sequence_newer(last_ack_, f.pose_sequence)) ++st_.ack_backwards;
    if (sent_stamp_[f.pose_sequence & 0xffff] != f.pose_timestamp_ns) ++st_.echo_mismatch;
    st_.lags.push_back(double(seq_ - f.pose_sequence));
    st_.rtts_us.push_back(double(t - f.pose_timestamp_ns) * 1e-3);
    last_ack_ = f.pose_sequence;
    have_ack_ = true;
  }
}

bool Client::wait_for_dentsph() {
  // The first valid message opens a session (a heartbeat: a hello would open a new one each
  // time), and dentsph sends a heartbeat every 100 ms while a session has no pose
  // (docs/haptic-protocol.md): the first message back says it listens.
  const auto until = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(o_.wait_s));
  auto heard = [&] { return st_.heartbeats + st_.forces + st_.malformed; };  // every message receive() counts
  const std::uint64_t before = heard();
  while (heard() == before && Clock::now() < until) {
    send_header(proto::Type::heartbeat);
    ++heartbeats_sent_;
    const auto next_beat = Clock::now() + std::chrono::milliseconds(100);
    while (heard() == before && Clock::now() < next_beat) {
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
      receive();
    }
  }
  return heard() > before;
}

void Client::hello() {
  send_header(proto::Type::hello);
  ++hellos_;
}

void Client::play() {
  const auto period = std::chrono::nanoseconds(std::int64_t(1e9 / o_.rate_hz));
  const auto start = Clock::now();
  auto next = start;
  double next_heartbeat = o_.heartbeat_every_s;
  for (;;) {
    std::this_thread::sleep_until(next);
    next += period;
    const double t = std::chrono::duration<double>(Clock::now() - start).count();
    if (t >= o_.duration_s) break;
    receive();
    if (o_.pause_at_s >= 0 && !paused_done_ && t >= o_.pause_at_s) {
      if (!held_.empty()) send(held_), held_.clear();
      std::this_thread::sleep_for(std::chrono::duration<double>(o_.pause_for_s));
      paused_done_ = true;
      next = Clock::now();
      continue;
    }
    if (o_.restart_at_s >= 0 && !restarted_ && t >= o_.restart_at_s) {
      restarted_ = true;
      ++restarts_;
      seq_ = 0;
      have_ack_ = false;
      if (o_.hello) hello();
    }
    if (o_.heartbeat_every_s > 0 && t >= next_heartbeat) {
      send_header(proto::Type::heartbeat);
      ++heartbeats_sent_;
      next_heartbeat += o_.heartbeat_every_s;
    }
    send_pose(t);
  }
}

void Client::send_pose(double t) {
  proto::PosePacket p;
  p.header.sequence = ++seq_;
  p.header.timestamp_ns = now_ns();
  if (o_.torque) p.capabilities = proto::kCapabilityTorque;
  for (int a = 0; a < 4; ++a) p.orientation[a] = o_.orientation[std::size_t(a)];
  sent_stamp_[seq_ & 0xffff] = p.header.timestamp_ns;
  const auto x = motion(o_, t);
  for (int a = 0; a < 3; ++a) p.position[a] = o_.scale * x[std::size_t(a)];
  if (o_.spike_at_s >= 0 && !spiked_ && t >= o_.spike_at_s) {
    spiked_ = true;
    ++spikes_;
    p.position[0] = o_.spike_m;
  }
  for (const double at : o_.press_button_at_s)
    if (t >= at && t < at + o_.press_button_for_s) p.buttons |= proto::kButtonDispense;
  if (o_.toggle_button_hz > 0 && std::fmod(t * o_.toggle_button_hz, 1.0) < 0.5) p.buttons |= proto::kButtonDispense;
  if (o_.toggle_light_hz > 0 && std::fmod(t * o_.toggle_light_hz, 1.0) < 0.5) p.buttons |= proto::kButtonLight;
  const std::size_t n = proto::encode(p, buf_);
  ++st_.poses_sent;
  const std::span<const std::uint8_t> pkt(buf_.data(), n);
  // One fault at most per pose, none on the pose that releases a held one, none in the last
  // 50 ms (so that every skipped pose is followed by one that reveals the gap).
  const double r = t < o_.duration_s - 0.05 ? u_(rng_) : 1.0;
  double c = 0;
  if (!held_.empty()) {
    send(pkt);
    send(held_);
    held_.clear();
  } else if (r < (c += o_.drop)) {
    ++st_.dropped;
  } else if (r < (c += o_.duplicate)) {
    send(pkt), send(pkt);
    ++st_.duplicated;
  } else if (r < (c += o_.reorder)) {
    held_.assign(pkt.begin(), pkt.end());
    ++st_.reordered;
  } else if (r < (c += o_.truncate)) {
    send(pkt.first(std::size_t(u_(rng_) * double(n - 1))));
    ++st_.truncated;
  } else {
    send(pkt);
  }
  if (u_(rng_) < o_.garbage && t < o_.duration_s - 0.05) {
    std::vector<std::uint8_t> g(1 + std::size_t(u_(rng_) * 200));
    for (auto& b : g) b = std::uint8_t(rng_());
    send(g);
    ++st_.garbage;
  }
}

void Client::leave() {
  if (!held_.empty()) send(held_);
  const auto drain_until = Clock::now() + std::chrono::milliseconds(20);
  while (Clock::now() < drain_until) {
    receive();
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  if (o_.bye) send_header(proto::Type::bye);
}

nlohmann::json Client::report() const {
  const Stats& st = st_;
  return {{"poses_sent", st.poses_sent},     {"dropped", st.dropped},
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
          {"hellos_sent", hellos_}, {"heartbeats_sent", heartbeats_sent_}, {"restarts", restarts_},
          {"spikes", spikes_}, {"forces_after_restart", forces_after_restart_},
          {"wrenches_received", st.wrenches}, {"max_torque_N_m", st.max_torque_N_m},
          {"torques_over_limit", st.torque_over_limit}, {"last_force_N", st.last_force},
          {"last_torque_N_m", st.last_torque}};
}

}  // namespace dentsph::haptic_client

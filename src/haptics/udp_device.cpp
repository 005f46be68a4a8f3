// The network bridge (docs/haptic-protocol.md): a client on the device's computer sends poses
// over UDP; each haptic tick drains the socket without blocking, keeps the newest pose and
// answers it with the force. One client at a time holds the session; it ends on "bye" or after
// session_timeout_s without a message it accepts, and a hello (or a restart of the client's pose
// numbers) starts a new one. Poses outside the workspace or faster than a hand are refused.
// Everything odd is counted, nothing stops the runtime.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <memory>
#include <stdexcept>

#include <fmt/format.h>

#include "dentsph/haptics/device.hpp"
#include "dentsph/haptics/protocol.hpp"

namespace dentsph {

namespace proto = haptic_protocol;

namespace {

constexpr int kMaxDatagramsPerTick = 256;
// The speed anchor's least age (s): with the 2 mm jitter tolerance, a pose may be at most 0.1 m/s
// faster than the speed limit over each anchor's span.
constexpr double kAnchorAge = 0.02;

struct UdpCounters {
  std::uint64_t datagrams = 0, poses = 0, duplicates = 0, reordered = 0, gaps = 0, too_old = 0;
  std::uint64_t malformed = 0, foreign = 0, heartbeats_received = 0, byes = 0, sessions = 0, timeouts = 0;
  std::uint64_t hellos = 0, restarts = 0, outside_workspace = 0, too_fast = 0;
  std::uint64_t forces_sent = 0, wrenches_sent = 0, heartbeats_sent = 0, send_errors = 0, receive_errors = 0;
  std::array<std::uint64_t, 7> malformed_by_reason{};
  double max_force_sent_N = 0, max_torque_sent_N_m = 0;
};

class UdpDeviceImpl final : public Device {
 public:
  explicit UdpDeviceImpl(const UdpDeviceOptions& o) : opt_(o) {
    fd_ = ::socket(AF_INET, SOCK_DGRAM, 0);
    if (fd_ < 0) throw std::runtime_error(fmt::format("UDP device: socket(): {}", std::strerror(errno)));
    const int rcvbuf = 1 << 20;
    ::setsockopt(fd_, SOL_SOCKET, SO_RCVBUF, &rcvbuf, sizeof rcvbuf);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(o.port);
    if (::inet_pton(AF_INET, o.address.c_str(), &a.sin_addr) != 1) {
      ::close(fd_);
      throw std::invalid_argument(fmt::format("UDP device: '{}' is not an IPv4 address (e.g. 127.0.0.1 or 0.0.0.0)", o.address));
    }
    if (::bind(fd_, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) {
      const int e = errno;
      ::close(fd_);
      throw std::runtime_error(fmt::format("UDP device: cannot listen on {}:{}: {}; choose another --port",
                                           o.address, o.port, std::strerror(e)));
    }
    socklen_t len = sizeof a;
    ::getsockname(fd_, reinterpret_cast<sockaddr*>(&a), &len);
    port_ = ntohs(a.sin_port);
  }
  ~UdpDeviceImpl() override { ::close(fd_); }
  UdpDeviceImpl(const UdpDeviceImpl&) = delete;
  UdpDeviceImpl& operator=(const UdpDeviceImpl&) = delete;

  std::uint16_t port() const { return port_; }
  std::string name() const override { return "udp"; }

  bool read(std::int64_t now_ns, DeviceSample& s) override {
    bool fresh = false;
    for (int i = 0; i < kMaxDatagramsPerTick; ++i) {
      sockaddr_in from{};
      socklen_t len = sizeof from;
      const ssize_t n = ::recvfrom(fd_, buf_.data(), buf_.size(), MSG_DONTWAIT, reinterpret_cast<sockaddr*>(&from), &len);
      if (n < 0) {
        if (errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR) ++c_.receive_errors;
        break;
      }
      ++c_.datagrams;
      fresh |= handle(std::span<const std::uint8_t>(buf_.data(), std::size_t(n)), from, now_ns, s);
    }
    if (session_ && double(now_ns - last_heard_ns_) * 1e-9 > opt_.session_timeout_s) {
      session_ = false;  // the client went quiet: another may connect
      ++c_.timeouts;
    }
    return fresh;
  }

  void write(std::int64_t now_ns, const ForceCommand& cmd) override {
    if (!session_) return;
    const double f2 = norm2(cmd.force_N);
    if (answer_pending_) {
      proto::ForcePacket p;
      p.header.sequence = ++out_sequence_;
      p.header.timestamp_ns = std::uint64_t(now_ns);
      p.force[0] = cmd.force_N.x, p.force[1] = cmd.force_N.y, p.force[2] = cmd.force_N.z;
      p.pose_sequence = answer_sequence_;
      p.pose_timestamp_ns = answer_timestamp_;
      p.status = cmd.status;
      p.force_age_us = cmd.force_age_us;
      p.torque[0] = cmd.torque_N_m.x, p.torque[1] = cmd.torque_N_m.y, p.torque[2] = cmd.torque_N_m.z;
      if (send(proto::encode(p, out_, torque_client_))) {
        ++c_.forces_sent;
        if (torque_client_) ++c_.wrenches_sent;
        if (f2 > c_.max_force_sent_N * c_.max_force_sent_N) c_.max_force_sent_N = std::sqrt(f2);
        c_.max_torque_sent_N_m = std::max(c_.max_torque_sent_N_m, norm(cmd.torque_N_m));
      }
      answer_pending_ = false;
      last_sent_ns_ = now_ns;
    } else if (double(now_ns - last_sent_ns_) * 1e-9 >= opt_.heartbeat_interval_s) {
      proto::Header h;
      h.type = proto::Type::heartbeat;
      h.sequence = ++out_sequence_;
      h.timestamp_ns = std::uint64_t(now_ns);
      if (send(proto::encode_header_only(h, out_))) ++c_.heartbeats_sent;
      last_sent_ns_ = now_ns;
    }
  }

  std::string report_json() const override {
    std::string reasons;
    for (std::size_t r = 1; r < c_.malformed_by_reason.size(); ++r)
      reasons += fmt::format("{}\"{}\": {}", reasons.empty() ? "" : ", ", proto::decode_error_name(proto::DecodeError(r)),
                             c_.malformed_by_reason[r]);
    const std::uint64_t lost = c_.gaps > c_.reordered ? c_.gaps - c_.reordered : 0;
    return fmt::format(
        "{{\"port\": {}, \"datagrams\": {}, \"poses\": {}, \"duplicates\": {}, \"reordered\": {}, \"lost\": {}, "
        "\"too_old\": {}, \"implausible\": {}, \"implausible_by_reason\": {{\"outside the workspace\": {}, "
        "\"faster than a hand\": {}}}, \"malformed\": {}, \"malformed_by_reason\": {{{}}}, \"foreign\": {}, "
        "\"heartbeats_received\": {}, \"hellos\": {}, \"byes\": {}, \"sessions\": {}, \"restarts\": {}, "
        "\"timeouts\": {}, \"forces_sent\": {}, \"wrenches_sent\": {}, \"heartbeats_sent\": {}, "
        "\"send_errors\": {}, \"receive_errors\": {}, \"max_force_sent_N\": {:.17g}, "
        "\"max_torque_sent_N_m\": {:.17g}}}",
        port_, c_.datagrams, c_.poses, c_.duplicates, c_.reordered, lost, c_.too_old,
        c_.outside_workspace + c_.too_fast, c_.outside_workspace, c_.too_fast, c_.malformed, reasons, c_.foreign,
        c_.heartbeats_received, c_.hellos, c_.byes, c_.sessions, c_.restarts, c_.timeouts, c_.forces_sent,
        c_.wrenches_sent, c_.heartbeats_sent, c_.send_errors, c_.receive_errors, c_.max_force_sent_N,
        c_.max_torque_sent_N_m);
  }

 private:
  bool same_client(const sockaddr_in& a) const {
    return a.sin_addr.s_addr == client_.sin_addr.s_addr && a.sin_port == client_.sin_port;
  }

  // A new session of the client at `from`: its pose numbers start again, and the runtime is told
  // (DeviceSample::session) to start the tool afresh.
  void start_session(const sockaddr_in& from) {
    session_ = true;
    client_ = from;
    have_pose_ = false;
    torque_client_ = false;  // until its poses say so
    seen_mask_ = 0;
    old_streak_ = 0;
    ++session_number_;
    ++c_.sessions;
  }

  // One datagram; returns true when it carried a new pose.
  bool handle(std::span<const std::uint8_t> d, const sockaddr_in& from, std::int64_t now_ns, DeviceSample& s) {
    proto::Header h;
    proto::DecodeError e = proto::decode_header(d, h);
    proto::PosePacket pose;
    if (e == proto::DecodeError::none && h.type == proto::Type::pose) e = proto::decode(d, pose);
    if (e == proto::DecodeError::none && (h.type == proto::Type::force || h.type == proto::Type::wrench))
      e = proto::DecodeError::bad_type;  // not ours
    if (e != proto::DecodeError::none) {
      ++c_.malformed;
      ++c_.malformed_by_reason[std::size_t(e)];
      return false;
    }
    if (session_ && !same_client(from)) {
      ++c_.foreign;
      return false;
    }
    if (h.type == proto::Type::bye) {
      if (session_) ++c_.byes, session_ = false;
      return false;
    }
    if (h.type == proto::Type::hello) {
      ++c_.hellos;
      start_session(from);  // a new session, from the client that holds it or a first one
      last_heard_ns_ = now_ns;
      return false;
    }
    if (!session_) start_session(from);  // the first valid message opens a session
    if (h.type == proto::Type::heartbeat) {
      ++c_.heartbeats_received;
      last_heard_ns_ = now_ns;
      return false;
    }
    return accept_pose(pose, now_ns, s);
  }

  // A pose in the workspace and no faster than a hand: from the pose received before it (by the
  // client's clock, or ours when the client's does not advance: so a pose that jumps away is
  // refused, and so is the one after it, which jumps back), and from the speed anchor, an
  // accepted pose at least `kAnchorAge` old (by the longer of the two clocks, so that the device
  // catches up, at a hand's speed, with a hand that really moved while its poses were refused).
  // The anchor moves only every kAnchorAge: measured from the pose just accepted, poses sent back
  // to back (a client catching up after a stall) would each be within the jitter tolerance of
  // the one before and creep away at any speed. Counted by reason when not.
  bool plausible(const proto::PosePacket& p, std::int64_t now_ns) {
    const Vec3 x{p.position[0], p.position[1], p.position[2]};
    const Vec3 previous = received_position_;
    const bool had_previous = have_received_;
    const double ours_prev = double(now_ns - received_ns_) * 1e-9;
    const double theirs_prev = double(std::int64_t(p.header.timestamp_ns - received_stamp_)) * 1e-9;
    have_received_ = true;
    received_position_ = x;
    received_ns_ = now_ns;
    received_stamp_ = p.header.timestamp_ns;
    if (!(norm(x) <= opt_.workspace_radius_m)) {
      ++c_.outside_workspace;
      return false;
    }
    auto too_fast = [&](const Vec3& from, double dt) {
      return norm(x - from) > opt_.max_speed_m_per_s * std::max(dt, 0.0) + opt_.jump_tolerance_m;
    };
    const double anchor_age = since_anchor(p, now_ns);
    if ((had_previous && too_fast(previous, theirs_prev > 0 && theirs_prev < 1 ? theirs_prev : ours_prev)) ||
        (have_accepted_ && too_fast(anchor_position_, anchor_age))) {
      ++c_.too_fast;
      return false;
    }
    return true;
  }

  // Seconds since the speed anchor, by the longer of our clock and the client's (when the
  // client's is plausible: forward and under a second).
  double since_anchor(const proto::PosePacket& p, std::int64_t now_ns) const {
    const double ours = double(now_ns - anchor_ns_) * 1e-9;
    const double theirs = double(std::int64_t(p.header.timestamp_ns - anchor_stamp_)) * 1e-9;
    return std::max(ours, theirs > 0 && theirs < 1 ? theirs : 0.0);
  }

  // Sequence bookkeeping over a 64-packet window behind the newest (as in IPsec's anti-replay
  // window): newer: accepted (a jump counts the skipped ones as gaps); within the window and
  // unseen: reordered (fills a gap, not used: a newer pose is already in hand); seen: duplicate;
  // further behind: too old. `restart_after` duplicates or too old poses in a row, each numbered
  // one after the previous, either from the start or sent after the newest pose (its timestamp),
  // are a client that numbers its poses from the start again: a new session.
  bool accept_pose(const proto::PosePacket& p, std::int64_t now_ns, DeviceSample& s) {
    const std::uint32_t q = p.header.sequence;
    if (have_pose_ && !proto::sequence_newer(q, newest_sequence_)) {
      const std::uint32_t behind = newest_sequence_ - q;
      const bool duplicate = behind == 0 || (behind < 64 && (seen_mask_ >> behind) & 1u);
      if (!duplicate && behind < 64) {
        seen_mask_ |= std::uint64_t(1) << behind;
        ++c_.reordered;
        last_heard_ns_ = now_ns;
        return false;
      }
      // A duplicate or a pose too old: refused, and it does not keep the session alive; but a run
      // of them numbered one after another is the client counting from the start again.
      // A run that numbers from the start (its first pose at most restart_after) or is sent now
      // (timestamps not older than the newest pose's: the client's clock went on) is; old poses
      // resent later with their old timestamps are not.
      const bool fresh = p.header.timestamp_ns >= newest_stamp_;
      const bool follows = old_streak_ > 0 && q == old_last_ + 1;
      old_streak_ = follows ? old_streak_ + 1 : 1;
      old_fresh_ = follows ? old_fresh_ && fresh : fresh;
      if (!follows) old_first_ = q;
      old_last_ = q;
      const bool from_start = old_first_ <= std::uint32_t(opt_.restart_after);
      if (old_streak_ < opt_.restart_after || !(from_start || old_fresh_)) {
        ++(duplicate ? c_.duplicates : c_.too_old);
        return false;
      }
      ++c_.restarts;
      start_session(client_);
    }
    old_streak_ = 0;
    if (have_pose_) {
      const std::uint32_t ahead = q - newest_sequence_;
      c_.gaps += ahead - 1;
      seen_mask_ = ahead < 64 ? (seen_mask_ << ahead) | 1u : 1u;
    } else {
      seen_mask_ = 1;
      have_accepted_ = have_received_ = false;
    }
    have_pose_ = true;
    newest_sequence_ = q;
    newest_stamp_ = p.header.timestamp_ns;
    ++c_.poses;
    if (!plausible(p, now_ns)) return false;  // arrived (not lost), but not used nor answered
    last_heard_ns_ = now_ns;
    accepted_position_ = {p.position[0], p.position[1], p.position[2]};
    if (!have_accepted_ || since_anchor(p, now_ns) >= kAnchorAge) {
      anchor_ns_ = now_ns;
      anchor_stamp_ = p.header.timestamp_ns;
      anchor_position_ = accepted_position_;
    }
    have_accepted_ = true;
    answer_sequence_ = q;
    answer_timestamp_ = p.header.timestamp_ns;
    s.pose.position = accepted_position_;
    s.pose.orientation = Quat{p.orientation[0], p.orientation[1], p.orientation[2], p.orientation[3]}.normalized();
    s.stamp_ns = now_ns;
    s.device_time_s = double(p.header.timestamp_ns) * 1e-9;
    s.sequence = q;
    s.buttons = p.buttons;
    torque_client_ = (p.capabilities & proto::kCapabilityTorque) != 0;
    s.session = session_number_;
    s.valid = true;
    answer_pending_ = true;
    return true;
  }

  bool send(std::size_t bytes) {
    const ssize_t n = ::sendto(fd_, out_.data(), bytes, MSG_DONTWAIT, reinterpret_cast<const sockaddr*>(&client_),
                               sizeof client_);
    if (n != ssize_t(bytes)) {
      ++c_.send_errors;
      return false;
    }
    return true;
  }

  UdpDeviceOptions opt_;
  int fd_ = -1;
  std::uint16_t port_ = 0;
  std::array<std::uint8_t, 2048> buf_{};
  std::array<std::uint8_t, proto::kMaxPacketBytes> out_{};
  bool session_ = false, torque_client_ = false, have_pose_ = false, have_accepted_ = false, have_received_ = false, answer_pending_ = false;
  sockaddr_in client_{};
  std::int64_t last_heard_ns_ = 0, last_sent_ns_ = 0, anchor_ns_ = 0, received_ns_ = 0;
  std::uint32_t newest_sequence_ = 0, out_sequence_ = 0, answer_sequence_ = 0, old_last_ = 0, session_number_ = 0;
  int old_streak_ = 0;
  bool old_fresh_ = false;            // every pose of the run sent after the newest pose
  std::uint32_t old_first_ = 0;       // the run's first pose number
  std::uint64_t newest_stamp_ = 0;    // the newest pose's timestamp (the client's clock)
  std::uint64_t answer_timestamp_ = 0, anchor_stamp_ = 0, received_stamp_ = 0, seen_mask_ = 0;
  Vec3 accepted_position_, anchor_position_, received_position_;
  UdpCounters c_;
};

}  // namespace

std::unique_ptr<Device> make_udp_device(const UdpDeviceOptions& options, std::uint16_t* bound_port) {
  auto d = std::make_unique<UdpDeviceImpl>(options);
  if (bound_port) *bound_port = d->port();
  return d;
}

}  // namespace dentsph

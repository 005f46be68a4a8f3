// The network bridge (docs/haptic-protocol.md): a client on the device's computer sends poses
// over UDP; each haptic tick drains the socket without blocking, keeps the newest pose and
// answers it with the force. One client at a time holds the session; it ends on "bye" or after
// session_timeout_s of silence. Everything odd is counted, nothing stops the runtime.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

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

struct UdpCounters {
  std::uint64_t datagrams = 0, poses = 0, duplicates = 0, reordered = 0, gaps = 0, too_old = 0;
  std::uint64_t malformed = 0, foreign = 0, heartbeats_received = 0, byes = 0, sessions = 0, timeouts = 0;
  std::uint64_t forces_sent = 0, heartbeats_sent = 0, send_errors = 0, receive_errors = 0;
  std::array<std::uint64_t, 7> malformed_by_reason{};
  double max_force_sent_N = 0;
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
      p.pose_sequence = newest_sequence_;
      p.pose_timestamp_ns = newest_timestamp_;
      p.status = cmd.status;
      p.force_age_us = cmd.force_age_us;
      if (send(proto::encode(p, out_))) {
        ++c_.forces_sent;
        if (f2 > c_.max_force_sent_N * c_.max_force_sent_N) c_.max_force_sent_N = std::sqrt(f2);
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
        "\"too_old\": {}, \"malformed\": {}, \"malformed_by_reason\": {{{}}}, \"foreign\": {}, "
        "\"heartbeats_received\": {}, \"byes\": {}, \"sessions\": {}, \"timeouts\": {}, \"forces_sent\": {}, "
        "\"heartbeats_sent\": {}, \"send_errors\": {}, \"receive_errors\": {}, \"max_force_sent_N\": {:.17g}}}",
        port_, c_.datagrams, c_.poses, c_.duplicates, c_.reordered, lost, c_.too_old, c_.malformed, reasons, c_.foreign,
        c_.heartbeats_received, c_.byes, c_.sessions, c_.timeouts, c_.forces_sent, c_.heartbeats_sent, c_.send_errors,
        c_.receive_errors, c_.max_force_sent_N);
  }

 private:
  bool same_client(const sockaddr_in& a) const {
    return a.sin_addr.s_addr == client_.sin_addr.s_addr && a.sin_port == client_.sin_port;
  }

  // One datagram; returns true when it carried a new pose.
  bool handle(std::span<const std::uint8_t> d, const sockaddr_in& from, std::int64_t now_ns, DeviceSample& s) {
    proto::Header h;
    proto::DecodeError e = proto::decode_header(d, h);
    proto::PosePacket pose;
    if (e == proto::DecodeError::none && h.type == proto::Type::pose) e = proto::decode(d, pose);
    if (e == proto::DecodeError::none && h.type == proto::Type::force) e = proto::DecodeError::bad_type;  // not ours
    if (e != proto::DecodeError::none) {
      ++c_.malformed;
      ++c_.malformed_by_reason[std::size_t(e)];
      return false;
    }
    if (!session_) {
      if (h.type == proto::Type::bye) return false;
      session_ = true;  // the first valid packet opens a session
      client_ = from;
      have_pose_ = false;
      seen_mask_ = 0;
      ++c_.sessions;
    } else if (!same_client(from)) {
      ++c_.foreign;
      return false;
    }
    last_heard_ns_ = now_ns;
    switch (h.type) {
      case proto::Type::heartbeat: ++c_.heartbeats_received; return false;
      case proto::Type::bye:
        ++c_.byes;
        session_ = false;
        return false;
      case proto::Type::force: return false;
      case proto::Type::pose: break;
    }
    return accept_pose(pose, now_ns, s);
  }

  // Sequence bookkeeping over a 64-packet window behind the newest (as in IPsec's anti-replay
  // window): newer: accepted (a jump counts the skipped ones as gaps); within the window and
  // unseen: reordered (fills a gap, not used: a newer pose is already in hand); seen: duplicate.
  bool accept_pose(const proto::PosePacket& p, std::int64_t now_ns, DeviceSample& s) {
    const std::uint32_t q = p.header.sequence;
    if (have_pose_ && !proto::sequence_newer(q, newest_sequence_)) {
      const std::uint32_t behind = newest_sequence_ - q;
      if (behind == 0 || (behind < 64 && (seen_mask_ >> behind) & 1u)) {
        ++c_.duplicates;
      } else if (behind < 64) {
        seen_mask_ |= std::uint64_t(1) << behind;
        ++c_.reordered;
      } else {
        ++c_.too_old;
      }
      return false;
    }
    if (have_pose_) {
      const std::uint32_t ahead = q - newest_sequence_;
      c_.gaps += ahead - 1;
      seen_mask_ = ahead < 64 ? (seen_mask_ << ahead) | 1u : 1u;
    } else {
      seen_mask_ = 1;
    }
    have_pose_ = true;
    newest_sequence_ = q;
    newest_timestamp_ = p.header.timestamp_ns;
    ++c_.poses;
    s.pose.position = {p.position[0], p.position[1], p.position[2]};
    s.pose.orientation = Quat{p.orientation[0], p.orientation[1], p.orientation[2], p.orientation[3]}.normalized();
    s.stamp_ns = now_ns;
    s.device_time_s = double(p.header.timestamp_ns) * 1e-9;
    s.sequence = q;
    s.buttons = p.buttons;
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
  bool session_ = false, have_pose_ = false, answer_pending_ = false;
  sockaddr_in client_{};
  std::int64_t last_heard_ns_ = 0, last_sent_ns_ = 0;
  std::uint32_t newest_sequence_ = 0, out_sequence_ = 0;
  std::uint64_t newest_timestamp_ = 0, seen_mask_ = 0;
  UdpCounters c_;
};

}  // namespace

std::unique_ptr<Device> make_udp_device(const UdpDeviceOptions& options, std::uint16_t* bound_port) {
  auto d = std::make_unique<UdpDeviceImpl>(options);
  if (bound_port) *bound_port = d->port();
  return d;
}

}  // namespace dentsph

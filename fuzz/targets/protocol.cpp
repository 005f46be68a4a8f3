// Fuzz target: the haptic bridge's datagrams. Each is decoded as a pose, a force or wrench and a header (a
// decoded one must encode back to the same bytes' meaning), then all are sent over loopback to a
// UDP device whose read and write the haptic loop's calls exercise: no crash, and every pose it
// hands on finite and within its workspace.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <span>

#include "dentsph/haptics/device.hpp"
#include "dentsph/haptics/protocol.hpp"
#include "fuzz_support.hpp"
#include "fuzz_targets.hpp"

namespace dentsph::fuzz {

namespace proto = haptic_protocol;

namespace {

void check(bool ok) {
  if (!ok) std::abort();  // a broken promise of the decoder or the device: a finding
}

void decode_all_ways(std::span<const std::uint8_t> d) {
  proto::Header h;
  (void)proto::decode_header(d, h);
  proto::PosePacket p;
  if (proto::decode(d, p) == proto::DecodeError::none) {
    for (double v : p.position) check(std::isfinite(v));
    std::array<std::uint8_t, proto::kMaxPacketBytes> out{};
    proto::PosePacket q;
    check(proto::decode(std::span<const std::uint8_t>(out.data(), proto::encode(p, out)), q) == proto::DecodeError::none);
    for (int i = 0; i < 3; ++i) check(q.position[i] == p.position[i]);
    check(q.header.sequence == p.header.sequence && q.buttons == p.buttons && q.capabilities == p.capabilities);
  }
  proto::ForcePacket f;
  if (proto::decode(d, f) == proto::DecodeError::none) {
    for (double v : f.force) check(std::isfinite(v));
    for (double v : f.torque) check(std::isfinite(v));
    // A wrench packet encodes back to itself; a force packet's torque reads zero.
    const bool wrench = f.header.type == proto::Type::wrench;
    std::array<std::uint8_t, proto::kMaxPacketBytes> out{};
    proto::ForcePacket g;
    check(proto::decode(std::span<const std::uint8_t>(out.data(), proto::encode(f, out, wrench)), g) ==
          proto::DecodeError::none);
    for (int i = 0; i < 3; ++i) check(g.force[i] == f.force[i] && g.torque[i] == f.torque[i]);
    if (!wrench) check(f.torque[0] == 0 && f.torque[1] == 0 && f.torque[2] == 0);
  }
}

}  // namespace

int protocol(const std::uint8_t* data, std::size_t size) {
  UdpDeviceOptions o;
  o.address = "127.0.0.1";
  o.port = 0;
  std::uint16_t port = 0;
  const std::unique_ptr<Device> device = make_udp_device(o, &port);
  const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(port);
  ::inet_pton(AF_INET, "127.0.0.1", &to.sin_addr);
  device->start(0);
  DeviceSample sample;
  std::int64_t now = 1'000'000;
  std::size_t at = 0, sent = 0;
  while (at < size) {
    const std::size_t n = std::min<std::size_t>(data[at], size - at - 1);
    const std::span<const std::uint8_t> d(data + at + 1, n);
    at += n + 1;
    decode_all_ways(d);
    ::sendto(fd, d.data(), d.size(), 0, reinterpret_cast<const sockaddr*>(&to), sizeof to);
    // Every few datagrams, a haptic tick 1 ms later (the device drains what arrived).
    if (++sent % 4 == 0) {
      now += 1'000'000;
      if (device->read(now, sample)) {
        check(is_finite(sample.pose.position) && norm(sample.pose.position) <= o.workspace_radius_m);
      }
      device->write(now, ForceCommand{{0.5, 0, 0}, {}, 0, 0});
    }
  }
  ::usleep(200);  // loopback delivery
  now += 1'000'000;
  if (device->read(now, sample)) check(is_finite(sample.pose.position) && norm(sample.pose.position) <= o.workspace_radius_m);
  device->write(now, ForceCommand{});
  (void)device->report_json();
  ::close(fd);
  return 0;
}

}  // namespace dentsph::fuzz

// The reference client's device (dentsph-haptic-client): a UDP socket to dentsph, the poses it
// sends at its rate with the faults it injects, and its checks of every force that comes back
// (finite, within the limit, answering a pose it sent) (docs/haptic-protocol.md).
#pragma once

#include <array>
#include <cstdint>
#include <random>
#include <span>
#include <vector>

#include <netinet/in.h>

#include <nlohmann/json.hpp>

#include "dentsph/haptics/protocol.hpp"
#include "options.hpp"

namespace dentsph::haptic_client {

namespace proto = haptic_protocol;

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

class Client {
 public:
  // Opens the socket to o.host:o.port; throws std::invalid_argument naming them when it cannot.
  explicit Client(const Options& o);
  ~Client();
  Client(const Client&) = delete;
  Client& operator=(const Client&) = delete;

  // --wait: a heartbeat every 100 ms until dentsph answers, at most o.wait_s; false when it never did.
  bool wait_for_dentsph();
  void hello();
  // The poses at o.rate_hz for o.duration_s (the motion, the buttons, the faults), reading the
  // forces between them.
  void play();
  // Sends a pose held back, reads the last forces for 20 ms, and says bye (unless --no-bye).
  void leave();
  // What the client saw (--report).
  nlohmann::json report() const;

 private:
  void send(std::span<const std::uint8_t> b);
  // hello, heartbeat and bye: the header alone, carrying the newest pose's number.
  void send_header(proto::Type type);
  // Reads every datagram waiting, checking each force.
  void receive();
  // One pose at time t, sent through the fault injection.
  void send_pose(double t);

  const Options& o_;
  int fd_ = -1;
  sockaddr_in to_{};
  std::mt19937 rng_;
  std::uniform_real_distribution<double> u_{0, 1};
  Stats st_;
  std::vector<std::uint64_t> sent_stamp_ = std::vector<std::uint64_t>(1 << 16, 0);  // each sequence's (mod 65536)
  std::uint32_t seq_ = 0, last_ack_ = 0;
  bool have_ack_ = false, restarted_ = false, paused_done_ = false, spiked_ = false;
  std::uint64_t forces_after_restart_ = 0, hellos_ = 0, heartbeats_sent_ = 0, restarts_ = 0, spikes_ = 0;
  std::vector<std::uint8_t> held_;  // a pose held back to be sent after the next one
  std::array<std::uint8_t, proto::kMaxPacketBytes> buf_{};
  std::array<std::uint8_t, 2048> in_{};
};

}  // namespace dentsph::haptic_client

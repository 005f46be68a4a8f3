// The haptic network bridge's wire format (docs/haptic-protocol.md): fixed-size UDP datagrams,
// little-endian, a 24-byte header and a payload per type. A client on the device's computer
// sends poses (and heartbeats), dentsph answers each with a force. Depends on nothing but the
// standard library, so the reference client and a client of any haptic SDK can use it alone.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

namespace dentsph::haptic_protocol {

inline constexpr std::array<std::uint8_t, 4> kMagic{'D', 'S', 'P', 'H'};
inline constexpr std::uint8_t kVersion = 1;
inline constexpr std::size_t kHeaderBytes = 24;

enum class Type : std::uint8_t {
  pose = 1,       // client -> dentsph: the device's pose
  force = 2,      // dentsph -> client: the force to render, answering the newest pose
  heartbeat = 3,  // either way: alive, nothing to say
  bye = 4,        // client -> dentsph: the session ends
  hello = 5,      // client -> dentsph: a new session starts (its pose numbers start again)
  wrench = 6,     // dentsph -> client: a force and a torque, answering the newest pose of a client
                  // that sets kCapabilityTorque in its poses
};

// Flags of a force packet (bit set: the condition holds).
enum ForceStatus : std::uint32_t {
  kSimStale = 1u << 0,      // no fresh simulation output: the watchdog is ramping the force down
  kPoseStale = 1u << 1,     // no fresh pose: the watchdog is ramping the force down
  kForceLimited = 1u << 2,  // the magnitude or rate limit of the device profile acted
  kNonFinite = 1u << 3,     // a non-finite force was computed and replaced by zero
};

// Bits of PosePacket::buttons (the device's buttons, pressed = 1).
inline constexpr std::uint32_t kButtonDispense = 1u << 0;  // button 1: dispense an increment (on press)
inline constexpr std::uint32_t kButtonLight = 1u << 1;     // button 2: the curing light on or off (on press)

// Bits of PosePacket::capabilities (what the client's device renders).
inline constexpr std::uint32_t kCapabilityTorque = 1u << 0;  // answer with wrench packets (force and torque)

struct Header {
  Type type = Type::heartbeat;
  std::uint16_t payload_bytes = 0;  // bytes after the header
  std::uint32_t sequence = 0;       // a client's poses: +1 per pose (wraps); dentsph's messages: +1
                                    // per message; a client's other messages: its newest pose's
  std::uint64_t timestamp_ns = 0;   // sender's monotonic clock when sent
};

struct PosePacket {
  Header header;
  double position[3] = {0, 0, 0};            // m, device frame
  double orientation[4] = {1, 0, 0, 0};      // unit quaternion w, x, y, z
  std::uint32_t buttons = 0;                 // bit mask (kButtonDispense)
  std::uint32_t capabilities = 0;            // bit mask (kCapabilityTorque); 0 from a version-1.0 client
};

struct ForcePacket {
  Header header;
  double force[3] = {0, 0, 0};        // N, device frame; finite and within the device's limit
  std::uint32_t pose_sequence = 0;    // sequence of the newest pose received (the one answered)
  std::uint32_t status = 0;           // ForceStatus bits
  std::uint64_t pose_timestamp_ns = 0;  // that pose's timestamp, echoed (client's clock)
  std::uint32_t force_age_us = 0;     // age of the simulation output inside this force
  std::uint32_t reserved = 0;
  double torque[3] = {0, 0, 0};       // N m about the tool's handle point, device frame; a wrench
                                      // packet only (zero where the device profile renders none)
};

inline constexpr std::size_t kPoseBytes = kHeaderBytes + 8 * 7 + 8;   // 88
inline constexpr std::size_t kForceBytes = kHeaderBytes + 8 * 3 + 24;  // 72
inline constexpr std::size_t kWrenchBytes = kForceBytes + 8 * 3;        // 96: a force packet, then the torque
inline constexpr std::size_t kMaxPacketBytes = 128;

// Why a datagram was refused.
enum class DecodeError { none, too_short, bad_magic, bad_version, bad_type, bad_length, non_finite };
const char* decode_error_name(DecodeError e);

// Encoders write exactly k*Bytes into `out` (which must hold them) and return the size.
std::size_t encode(const PosePacket& p, std::span<std::uint8_t> out);
// A force packet (72 bytes), or with `torque` a wrench packet (96 bytes).
std::size_t encode(const ForcePacket& p, std::span<std::uint8_t> out, bool torque = false);
std::size_t encode_header_only(const Header& h, std::span<std::uint8_t> out);  // heartbeat, bye, hello

// Reads the header of a datagram and checks magic, version, type and that the length is exactly
// that type's size.
DecodeError decode_header(std::span<const std::uint8_t> in, Header& h);
DecodeError decode(std::span<const std::uint8_t> in, PosePacket& p);   // also: finite, |q| > 0
// A force or a wrench packet (a force packet's torque reads zero); also: finite force and torque.
DecodeError decode(std::span<const std::uint8_t> in, ForcePacket& p);

// Serial-number arithmetic on 32-bit sequences (RFC 1982): a is newer than b.
inline bool sequence_newer(std::uint32_t a, std::uint32_t b) {
  return a != b && std::uint32_t(a - b) < 0x80000000u;
}

}  // namespace dentsph::haptic_protocol

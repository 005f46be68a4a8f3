// Encoding and decoding of the bridge's datagrams: explicit little-endian byte order, every field
// at a fixed offset (docs/haptic-protocol.md), nothing trusted before it is checked.
#include "dentsph/haptics/protocol.hpp"

#include <bit>
#include <cmath>
#include <cstring>

namespace dentsph::haptic_protocol {

namespace {

// Little-endian writer and reader over a byte span whose size the caller has checked.
struct Writer {
  std::uint8_t* p;
  template <class U>
  void uint(U v) {
    for (std::size_t i = 0; i < sizeof(U); ++i) *p++ = std::uint8_t(v >> (8 * i));
  }
  void f64(double v) { uint(std::bit_cast<std::uint64_t>(v)); }
  void bytes(const std::uint8_t* b, std::size_t n) {
    std::memcpy(p, b, n);
    p += n;
  }
};

struct ReaderLE {
  const std::uint8_t* p;
  template <class U>
  U uint() {
    U v = 0;
    for (std::size_t i = 0; i < sizeof(U); ++i) v = U(v | (U(*p++) << (8 * i)));
    return v;
  }
  double f64() { return std::bit_cast<double>(uint<std::uint64_t>()); }
};

void write_header(Writer& w, const Header& h) {
  w.bytes(kMagic.data(), kMagic.size());
  w.uint<std::uint8_t>(kVersion);
  w.uint<std::uint8_t>(std::uint8_t(h.type));
  w.uint<std::uint16_t>(h.payload_bytes);
  w.uint<std::uint32_t>(h.sequence);
  w.uint<std::uint32_t>(0);  // reserved
  w.uint<std::uint64_t>(h.timestamp_ns);
}

std::size_t expected_size(Type t) {
  switch (t) {
    case Type::pose: return kPoseBytes;
    case Type::force: return kForceBytes;
    case Type::wrench: return kWrenchBytes;
    case Type::heartbeat:
    case Type::bye:
    case Type::hello: return kHeaderBytes;
  }
  return 0;
}

}  // namespace

const char* decode_error_name(DecodeError e) {
  switch (e) {
    case DecodeError::none: return "none";
    case DecodeError::too_short: return "shorter than a header";
    case DecodeError::bad_magic: return "not a dentsph packet (magic)";
    case DecodeError::bad_version: return "unsupported protocol version";
    case DecodeError::bad_type: return "unknown packet type";
    case DecodeError::bad_length: return "length does not match the packet type";
    case DecodeError::non_finite: return "non-finite or invalid value";
  }
  return "?";
}

// A writer positioned after a header of `type` for a message of `total` bytes.
static Writer begin(const Header& header, Type type, std::size_t total, std::span<std::uint8_t> out) {
  Header h = header;
  h.type = type;
  h.payload_bytes = std::uint16_t(total - kHeaderBytes);
  Writer w{out.data()};
  write_header(w, h);
  return w;
}

std::size_t encode_header_only(const Header& h, std::span<std::uint8_t> out) {
  begin(h, h.type, kHeaderBytes, out);
  return kHeaderBytes;
}

std::size_t encode(const PosePacket& p, std::span<std::uint8_t> out) {
  Writer w = begin(p.header, Type::pose, kPoseBytes, out);
  for (double v : p.position) w.f64(v);
  for (double v : p.orientation) w.f64(v);
  w.uint<std::uint32_t>(p.buttons);
  w.uint<std::uint32_t>(p.capabilities);
  return kPoseBytes;
}

std::size_t encode(const ForcePacket& p, std::span<std::uint8_t> out, bool torque) {
  Writer w = begin(p.header, torque ? Type::wrench : Type::force, torque ? kWrenchBytes : kForceBytes, out);
  for (double v : p.force) w.f64(v);
  w.uint<std::uint32_t>(p.pose_sequence);
  w.uint<std::uint32_t>(p.status);
  w.uint<std::uint64_t>(p.pose_timestamp_ns);
  w.uint<std::uint32_t>(p.force_age_us);
  w.uint<std::uint32_t>(p.reserved);
  if (!torque) return kForceBytes;
  for (double v : p.torque) w.f64(v);
  return kWrenchBytes;
}

DecodeError decode_header(std::span<const std::uint8_t> in, Header& h) {
  if (in.size() < kHeaderBytes) return DecodeError::too_short;
  if (std::memcmp(in.data(), kMagic.data(), kMagic.size()) != 0) return DecodeError::bad_magic;
  ReaderLE r{in.data() + 4};
  if (r.uint<std::uint8_t>() != kVersion) return DecodeError::bad_version;
  const std::uint8_t type = r.uint<std::uint8_t>();
  if (type < std::uint8_t(Type::pose) || type > std::uint8_t(Type::wrench)) return DecodeError::bad_type;
  h.type = Type(type);
  h.payload_bytes = r.uint<std::uint16_t>();
  h.sequence = r.uint<std::uint32_t>();
  r.uint<std::uint32_t>();  // reserved
  h.timestamp_ns = r.uint<std::uint64_t>();
  if (in.size() != expected_size(h.type) || h.payload_bytes != in.size() - kHeaderBytes)
    return DecodeError::bad_length;
  return DecodeError::none;
}

DecodeError decode(std::span<const std::uint8_t> in, PosePacket& p) {
  if (const DecodeError e = decode_header(in, p.header); e != DecodeError::none) return e;
  if (p.header.type != Type::pose) return DecodeError::bad_type;
  ReaderLE r{in.data() + kHeaderBytes};
  for (double& v : p.position) v = r.f64();
  for (double& v : p.orientation) v = r.f64();
  p.buttons = r.uint<std::uint32_t>();
  p.capabilities = r.uint<std::uint32_t>();
  double q2 = 0;
  for (double v : p.position)
    if (!std::isfinite(v)) return DecodeError::non_finite;
  for (double v : p.orientation) {
    if (!std::isfinite(v)) return DecodeError::non_finite;
    q2 += v * v;
  }
  if (!(q2 > 1e-12)) return DecodeError::non_finite;
  return DecodeError::none;
}

DecodeError decode(std::span<const std::uint8_t> in, ForcePacket& p) {
  if (const DecodeError e = decode_header(in, p.header); e != DecodeError::none) return e;
  if (p.header.type != Type::force && p.header.type != Type::wrench) return DecodeError::bad_type;
  ReaderLE r{in.data() + kHeaderBytes};
  for (double& v : p.force) v = r.f64();
  p.pose_sequence = r.uint<std::uint32_t>();
  p.status = r.uint<std::uint32_t>();
  p.pose_timestamp_ns = r.uint<std::uint64_t>();
  p.force_age_us = r.uint<std::uint32_t>();
  p.reserved = r.uint<std::uint32_t>();
  for (double& v : p.torque) v = p.header.type == Type::wrench ? r.f64() : 0.0;
  for (double v : p.force)
    if (!std::isfinite(v)) return DecodeError::non_finite;
  for (double v : p.torque)
    if (!std::isfinite(v)) return DecodeError::non_finite;
  return DecodeError::none;
}

}  // namespace dentsph::haptic_protocol

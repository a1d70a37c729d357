#include "haptics/rig_protocol.h"

namespace serosa::haptics {
namespace {

// Byte offsets (docs/rig-protocol.md has the same tables).
constexpr std::size_t kOffType = 0;
constexpr std::size_t kOffVersion = 1;
constexpr std::size_t kOffLength = 2;
constexpr std::size_t kOffSequence = 4;
constexpr std::size_t kStateOffTime = 8;
constexpr std::size_t kStateOffHandles = 12;
constexpr std::size_t kStateHandleSize = 22;
constexpr std::size_t kStateOffStatus = 56;
constexpr std::size_t kStateOffCrc = 62;
constexpr std::size_t kForceOffStateSeq = 8;
constexpr std::size_t kForceOffHandles = 12;
constexpr std::size_t kForceHandleSize = 10;
constexpr std::size_t kForceOffFlags = 32;
constexpr std::size_t kForceOffCrc = 34;

constexpr std::array<std::uint16_t, 256> make_crc_table() {
  std::array<std::uint16_t, 256> t{};
  for (std::uint32_t i = 0; i < 256; ++i) {
    std::uint32_t c = i << 8;
    for (int b = 0; b < 8; ++b) c = (c & 0x8000u) ? ((c << 1) ^ 0x1021u) : (c << 1);
    t[i] = static_cast<std::uint16_t>(c & 0xffffu);
  }
  return t;
}
constexpr std::array<std::uint16_t, 256> kCrcTable = make_crc_table();

void put_u16(std::uint8_t* p, std::uint16_t v) {
  p[0] = static_cast<std::uint8_t>(v & 0xffu);
  p[1] = static_cast<std::uint8_t>(v >> 8);
}
void put_u32(std::uint8_t* p, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) p[i] = static_cast<std::uint8_t>((v >> (8 * i)) & 0xffu);
}
std::uint16_t get_u16(const std::uint8_t* p) {
  return static_cast<std::uint16_t>(p[0] | (p[1] << 8));
}
std::uint32_t get_u32(const std::uint8_t* p) {
  std::uint32_t v = 0;
  for (int i = 0; i < 4; ++i) v |= static_cast<std::uint32_t>(p[i]) << (8 * i);
  return v;
}
void put_i32(std::uint8_t* p, std::int32_t v) { put_u32(p, static_cast<std::uint32_t>(v)); }
void put_i16(std::uint8_t* p, std::int16_t v) { put_u16(p, static_cast<std::uint16_t>(v)); }
std::int32_t get_i32(const std::uint8_t* p) { return static_cast<std::int32_t>(get_u32(p)); }
std::int16_t get_i16(const std::uint8_t* p) { return static_cast<std::int16_t>(get_u16(p)); }

// Shared header checks: size, checksum, type, version, length field (in that order).
DecodeError check(std::span<const std::uint8_t> bytes, std::size_t size, std::uint8_t type) {
  if (bytes.size() < size) return DecodeError::kTooShort;
  if (bytes.size() > size) return DecodeError::kTooLong;
  const std::uint16_t crc = crc16_ccitt(bytes.first(size - 2));
  if (crc != get_u16(bytes.data() + size - 2)) return DecodeError::kBadChecksum;
  if (bytes[kOffType] != type) return DecodeError::kWrongType;
  if (bytes[kOffVersion] != kProtocolVersion) return DecodeError::kBadVersion;
  if (get_u16(bytes.data() + kOffLength) != size) return DecodeError::kLengthField;
  return DecodeError::kOk;
}

}  // namespace

std::string_view to_string(DecodeError e) noexcept {
  switch (e) {
    case DecodeError::kOk:
      return "ok";
    case DecodeError::kTooShort:
      return "packet too short (truncated transfer)";
    case DecodeError::kTooLong:
      return "packet too long";
    case DecodeError::kBadChecksum:
      return "CRC-16 checksum mismatch";
    case DecodeError::kWrongType:
      return "wrong packet type byte";
    case DecodeError::kBadVersion:
      return "unsupported protocol version";
    case DecodeError::kLengthField:
      return "length field disagrees with the packet size";
  }
  return "unknown decode error";
}

std::uint16_t crc16_ccitt(std::span<const std::uint8_t> bytes) noexcept {
  std::uint16_t crc = 0xffff;
  for (const std::uint8_t b : bytes) {
    crc = static_cast<std::uint16_t>((crc << 8) ^ kCrcTable[((crc >> 8) ^ b) & 0xffu]);
  }
  return crc;
}

void encode_state(const StatePacket& p, std::span<std::uint8_t, kStatePacketSize> out) noexcept {
  std::uint8_t* b = out.data();
  for (std::size_t i = 0; i < kStatePacketSize; ++i) b[i] = 0;
  b[kOffType] = kStateType;
  b[kOffVersion] = p.version;
  put_u16(b + kOffLength, static_cast<std::uint16_t>(kStatePacketSize));
  put_u32(b + kOffSequence, p.sequence);
  put_u32(b + kStateOffTime, p.device_time_us);
  for (std::size_t h = 0; h < kHandles; ++h) {
    std::uint8_t* q = b + kStateOffHandles + h * kStateHandleSize;
    const HandleCounts& c = p.handles[h];
    put_i32(q + 0, c.pitch);
    put_i32(q + 4, c.yaw);
    put_i32(q + 8, c.roll);
    put_i32(q + 12, c.insertion);
    put_i32(q + 16, c.jaw);
    put_u16(q + 20, c.buttons);
  }
  put_u16(b + kStateOffStatus, p.status);
  put_u16(b + kStateOffCrc, crc16_ccitt(std::span<const std::uint8_t>(b, kStateOffCrc)));
}

void encode_force(const ForcePacket& p, std::span<std::uint8_t, kForcePacketSize> out) noexcept {
  std::uint8_t* b = out.data();
  for (std::size_t i = 0; i < kForcePacketSize; ++i) b[i] = 0;
  b[kOffType] = kForceType;
  b[kOffVersion] = p.version;
  put_u16(b + kOffLength, static_cast<std::uint16_t>(kForcePacketSize));
  put_u32(b + kOffSequence, p.sequence);
  put_u32(b + kForceOffStateSeq, p.state_sequence);
  for (std::size_t h = 0; h < kHandles; ++h) {
    std::uint8_t* q = b + kForceOffHandles + h * kForceHandleSize;
    const HandleEffort& e = p.handles[h];
    put_i16(q + 0, e.pitch_torque);
    put_i16(q + 2, e.yaw_torque);
    put_i16(q + 4, e.roll_torque);
    put_i16(q + 6, e.insertion_force);
    put_i16(q + 8, e.jaw_torque);
  }
  put_u16(b + kForceOffFlags, p.flags);
  put_u16(b + kForceOffCrc, crc16_ccitt(std::span<const std::uint8_t>(b, kForceOffCrc)));
}

DecodeError decode_state(std::span<const std::uint8_t> bytes, StatePacket& out) noexcept {
  const DecodeError e = check(bytes, kStatePacketSize, kStateType);
  if (e != DecodeError::kOk) return e;
  const std::uint8_t* b = bytes.data();
  StatePacket p;
  p.version = b[kOffVersion];
  p.sequence = get_u32(b + kOffSequence);
  p.device_time_us = get_u32(b + kStateOffTime);
  for (std::size_t h = 0; h < kHandles; ++h) {
    const std::uint8_t* q = b + kStateOffHandles + h * kStateHandleSize;
    HandleCounts& c = p.handles[h];
    c.pitch = get_i32(q + 0);
    c.yaw = get_i32(q + 4);
    c.roll = get_i32(q + 8);
    c.insertion = get_i32(q + 12);
    c.jaw = get_i32(q + 16);
    c.buttons = get_u16(q + 20);
  }
  p.status = get_u16(b + kStateOffStatus);
  out = p;
  return DecodeError::kOk;
}

DecodeError decode_force(std::span<const std::uint8_t> bytes, ForcePacket& out) noexcept {
  const DecodeError e = check(bytes, kForcePacketSize, kForceType);
  if (e != DecodeError::kOk) return e;
  const std::uint8_t* b = bytes.data();
  ForcePacket p;
  p.version = b[kOffVersion];
  p.sequence = get_u32(b + kOffSequence);
  p.state_sequence = get_u32(b + kForceOffStateSeq);
  for (std::size_t h = 0; h < kHandles; ++h) {
    const std::uint8_t* q = b + kForceOffHandles + h * kForceHandleSize;
    HandleEffort& f = p.handles[h];
    f.pitch_torque = get_i16(q + 0);
    f.yaw_torque = get_i16(q + 2);
    f.roll_torque = get_i16(q + 4);
    f.insertion_force = get_i16(q + 6);
    f.jaw_torque = get_i16(q + 8);
  }
  p.flags = get_u16(b + kForceOffFlags);
  out = p;
  return DecodeError::kOk;
}

}  // namespace serosa::haptics

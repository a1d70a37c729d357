// Rig protocol: the wire format of the two-handle laparoscopic USB rig (docs/rig-protocol.md).
//
// Two packet kinds travel over two interrupt endpoints at 1 kHz, all fields little-endian:
//   StatePacket  (device -> host, EP 0x81 IN,  64 bytes): both handles' encoder counts, jaw
//                counts, buttons, a status word, a sequence number and a CRC-16.
//   ForcePacket  (host -> device, EP 0x01 OUT, 36 bytes): per handle four joint efforts and a jaw
//                torque in fixed point, an enable flag, the echo of the state sequence it answers,
//                and a CRC-16.
// decode_*() validate strictly (length, checksum, type, version, length field) and say which
// check failed; encode_*() never fail. No allocation anywhere: safe inside the 1 kHz loop.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

namespace serosa::haptics {

// USB identity (pid.codes open-source vendor id; the product id is the rig's assignment).
inline constexpr std::uint16_t kRigVendorId = 0x1209;
inline constexpr std::uint16_t kRigProductId = 0x5e70;
inline constexpr std::uint8_t kRigInterface = 0;
inline constexpr std::uint8_t kRigStateEndpoint = 0x81;  ///< interrupt IN, 64 bytes, 1 ms
inline constexpr std::uint8_t kRigForceEndpoint = 0x01;  ///< interrupt OUT, 64 bytes, 1 ms

inline constexpr std::uint8_t kProtocolVersion = 1;
inline constexpr std::uint8_t kStateType = 0x53;  ///< 'S'
inline constexpr std::uint8_t kForceType = 0x46;  ///< 'F'
inline constexpr std::size_t kStatePacketSize = 64;
inline constexpr std::size_t kForcePacketSize = 36;
inline constexpr std::size_t kHandles = 2;

/// Fixed-point scales of the force packet (value = raw * scale).
inline constexpr double kTorqueScaleNm = 1e-4;  ///< pitch, yaw, roll, jaw torque: 0.1 mN*m / LSB
inline constexpr double kForceScaleN = 1e-3;    ///< insertion force: 1 mN / LSB

/// Status bits of StatePacket::status.
enum StatusBits : std::uint16_t {
  kStatusMotorsEnabled = 1u << 0,    ///< amplifiers powered and following force packets
  kStatusWatchdogTripped = 1u << 1,  ///< no valid force packet for 2 ms: motors forced to zero
  kStatusOverTemperature = 1u << 2,  ///< amplifier thermal limit: firmware scales forces down
  kStatusHandleMissing0 = 1u << 3,   ///< handle 0 not connected to the base
  kStatusHandleMissing1 = 1u << 4,   ///< handle 1 not connected to the base
};

/// One handle's raw readings.
struct HandleCounts {
  std::int32_t pitch = 0;      ///< pitch encoder, counts (signed, 0 = calibrated zero)
  std::int32_t yaw = 0;        ///< yaw encoder, counts
  std::int32_t roll = 0;       ///< roll (about the shaft) encoder, counts
  std::int32_t insertion = 0;  ///< insertion encoder, counts (0 = tip at the trocar pivot)
  std::int32_t jaw = 0;        ///< jaw encoder, counts (0 = closed)
  std::uint16_t buttons = 0;   ///< bit mask: bit 0 clutch, bit 1 cautery pedal, bit 2 handle btn
};

/// Device -> host, one per millisecond.
struct StatePacket {
  std::uint8_t version = kProtocolVersion;
  std::uint32_t sequence = 0;        ///< increments by one per packet, wraps at 2^32
  std::uint32_t device_time_us = 0;  ///< device clock, microseconds, wraps
  std::array<HandleCounts, kHandles> handles{};
  std::uint16_t status = 0;  ///< StatusBits
};

/// One handle's commanded efforts, raw fixed point (see kTorqueScaleNm, kForceScaleN).
struct HandleEffort {
  std::int16_t pitch_torque = 0;     ///< about the pitch axis, 1e-4 N*m
  std::int16_t yaw_torque = 0;       ///< about the yaw axis, 1e-4 N*m
  std::int16_t roll_torque = 0;      ///< about the shaft, 1e-4 N*m
  std::int16_t insertion_force = 0;  ///< along the shaft (+ = pushes the tool in), 1e-3 N
  std::int16_t jaw_torque = 0;       ///< jaw (+ = opens), 1e-4 N*m
};

/// Host -> device, one per loop tick.
struct ForcePacket {
  std::uint8_t version = kProtocolVersion;
  std::uint32_t sequence = 0;        ///< host sequence, increments by one per packet
  std::uint32_t state_sequence = 0;  ///< sequence of the StatePacket this command answers
  std::array<HandleEffort, kHandles> handles{};
  std::uint16_t flags = 0;  ///< bit 0: enable motors (0 = all efforts ignored, zero)
};

inline constexpr std::uint16_t kForceEnable = 1u << 0;

/// Why a packet was rejected. Checks run in this order: size, checksum, type, version, length.
enum class DecodeError : std::uint8_t {
  kOk = 0,
  kTooShort,     ///< fewer bytes than the packet size (truncated transfer)
  kTooLong,      ///< more bytes than the packet size
  kBadChecksum,  ///< CRC-16 over the packet does not match its last two bytes
  kWrongType,    ///< type byte is not the expected packet kind
  kBadVersion,   ///< version byte is not kProtocolVersion
  kLengthField,  ///< the packet's own length field disagrees with the packet size
};

/// A short, human-readable description of the error ("ok" for kOk).
[[nodiscard]] std::string_view to_string(DecodeError e) noexcept;

/// CRC-16/CCITT-FALSE: polynomial 0x1021, init 0xFFFF, no reflection, no final xor.
/// Detects every single-bit error, every odd number of bit errors and every burst up to 16 bits.
[[nodiscard]] std::uint16_t crc16_ccitt(std::span<const std::uint8_t> bytes) noexcept;

/// Writes the 64-byte wire form of p into out.
void encode_state(const StatePacket& p, std::span<std::uint8_t, kStatePacketSize> out) noexcept;
/// Writes the 36-byte wire form of p into out.
void encode_force(const ForcePacket& p, std::span<std::uint8_t, kForcePacketSize> out) noexcept;

/// Parses and validates a state packet; on error `out` is left unchanged.
[[nodiscard]] DecodeError decode_state(std::span<const std::uint8_t> bytes,
                                       StatePacket& out) noexcept;
/// Parses and validates a force packet; on error `out` is left unchanged.
[[nodiscard]] DecodeError decode_force(std::span<const std::uint8_t> bytes,
                                       ForcePacket& out) noexcept;

}  // namespace serosa::haptics

// Property tests of the rig packet codec: round trips, every single-bit flip detected, truncation.
#include <gtest/gtest.h>

#include <array>
#include <cstring>
#include <random>
#include <vector>

#include "haptics/rig_protocol.h"

namespace serosa::haptics {
namespace {

StatePacket random_state(std::mt19937& rng) {
  std::uniform_int_distribution<std::int32_t> i32;
  std::uniform_int_distribution<std::uint32_t> u32;
  std::uniform_int_distribution<int> u16(0, 0xffff);
  StatePacket p;
  p.sequence = u32(rng);
  p.device_time_us = u32(rng);
  for (auto& h : p.handles) {
    h.pitch = i32(rng);
    h.yaw = i32(rng);
    h.roll = i32(rng);
    h.insertion = i32(rng);
    h.jaw = i32(rng);
    h.buttons = static_cast<std::uint16_t>(u16(rng));
  }
  p.status = static_cast<std::uint16_t>(u16(rng));
  return p;
}

ForcePacket random_force(std::mt19937& rng) {
  std::uniform_int_distribution<std::uint32_t> u32;
  std::uniform_int_distribution<int> i16(-32768, 32767);
  ForcePacket p;
  p.sequence = u32(rng);
  p.state_sequence = u32(rng);
  for (auto& h : p.handles) {
    h.pitch_torque = static_cast<std::int16_t>(i16(rng));
    h.yaw_torque = static_cast<std::int16_t>(i16(rng));
    h.roll_torque = static_cast<std::int16_t>(i16(rng));
    h.insertion_force = static_cast<std::int16_t>(i16(rng));
    h.jaw_torque = static_cast<std::int16_t>(i16(rng));
  }
  p.flags = static_cast<std::uint16_t>(i16(rng) & 0xffff);
  return p;
}

bool equal(const StatePacket& a, const StatePacket& b) {
  if (a.version != b.version || a.sequence != b.sequence || a.device_time_us != b.device_time_us ||
      a.status != b.status)
    return false;
  for (std::size_t h = 0; h < kHandles; ++h) {
    const auto& x = a.handles[h];
    const auto& y = b.handles[h];
    if (x.pitch != y.pitch || x.yaw != y.yaw || x.roll != y.roll || x.insertion != y.insertion ||
        x.jaw != y.jaw || x.buttons != y.buttons)
      return false;
  }
  return true;
}

bool equal(const ForcePacket& a, const ForcePacket& b) {
  if (a.version != b.version || a.sequence != b.sequence || a.state_sequence != b.state_sequence ||
      a.flags != b.flags)
    return false;
  for (std::size_t h = 0; h < kHandles; ++h) {
    const auto& x = a.handles[h];
    const auto& y = b.handles[h];
    if (x.pitch_torque != y.pitch_torque || x.yaw_torque != y.yaw_torque ||
        x.roll_torque != y.roll_torque || x.insertion_force != y.insertion_force ||
        x.jaw_torque != y.jaw_torque)
      return false;
  }
  return true;
}

TEST(RigProtocol, CrcKnownAnswer) {
  // CRC-16/CCITT-FALSE check value of "123456789".
  const char* s = "123456789";
  std::array<std::uint8_t, 9> b{};
  std::memcpy(b.data(), s, 9);
  EXPECT_EQ(crc16_ccitt(b), 0x29b1);
}

TEST(RigProtocol, StateRoundTrip) {
  std::mt19937 rng(1);
  for (int i = 0; i < 2000; ++i) {
    const StatePacket p = random_state(rng);
    std::array<std::uint8_t, kStatePacketSize> wire{};
    encode_state(p, wire);
    StatePacket q;
    ASSERT_EQ(decode_state(wire, q), DecodeError::kOk);
    ASSERT_TRUE(equal(p, q)) << "packet " << i;
  }
}

TEST(RigProtocol, ForceRoundTrip) {
  std::mt19937 rng(2);
  for (int i = 0; i < 2000; ++i) {
    const ForcePacket p = random_force(rng);
    std::array<std::uint8_t, kForcePacketSize> wire{};
    encode_force(p, wire);
    ForcePacket q;
    ASSERT_EQ(decode_force(wire, q), DecodeError::kOk);
    ASSERT_TRUE(equal(p, q)) << "packet " << i;
  }
}

TEST(RigProtocol, LittleEndianLayout) {
  StatePacket p;
  p.sequence = 0x04030201u;
  p.handles[0].pitch = -2;  // 0xfffffffe
  p.handles[1].buttons = 0x0102;
  p.status = 0x0a0b;
  std::array<std::uint8_t, kStatePacketSize> w{};
  encode_state(p, w);
  EXPECT_EQ(w[0], kStateType);
  EXPECT_EQ(w[1], kProtocolVersion);
  EXPECT_EQ(w[2], 64);
  EXPECT_EQ(w[3], 0);
  EXPECT_EQ(w[4], 1);
  EXPECT_EQ(w[7], 4);
  EXPECT_EQ(w[12], 0xfe);
  EXPECT_EQ(w[15], 0xff);
  EXPECT_EQ(w[34 + 20], 0x02);
  EXPECT_EQ(w[34 + 21], 0x01);
  EXPECT_EQ(w[56], 0x0b);
  EXPECT_EQ(w[57], 0x0a);
  const std::uint16_t crc = crc16_ccitt(std::span<const std::uint8_t>(w.data(), 62));
  EXPECT_EQ(w[62], crc & 0xff);
  EXPECT_EQ(w[63], crc >> 8);
}

TEST(RigProtocol, EverySingleBitFlipIsDetected) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 20; ++trial) {
    std::array<std::uint8_t, kStatePacketSize> ws{};
    encode_state(random_state(rng), ws);
    for (std::size_t bit = 0; bit < ws.size() * 8; ++bit) {
      auto w = ws;
      w[bit / 8] ^= static_cast<std::uint8_t>(1u << (bit % 8));
      StatePacket out;
      out.sequence = 0xdeadbeef;
      ASSERT_NE(decode_state(w, out), DecodeError::kOk) << "state bit " << bit;
      ASSERT_EQ(out.sequence, 0xdeadbeefu) << "output touched on error";
    }
    std::array<std::uint8_t, kForcePacketSize> wf{};
    encode_force(random_force(rng), wf);
    for (std::size_t bit = 0; bit < wf.size() * 8; ++bit) {
      auto w = wf;
      w[bit / 8] ^= static_cast<std::uint8_t>(1u << (bit % 8));
      ForcePacket out;
      ASSERT_NE(decode_force(w, out), DecodeError::kOk) << "force bit " << bit;
    }
  }
}

TEST(RigProtocol, FlipsOutsideTheChecksumAreChecksumErrors) {
  // A flip in the body is reported as a checksum error (the checksum is checked first).
  std::array<std::uint8_t, kStatePacketSize> w{};
  encode_state(StatePacket{}, w);
  w[20] ^= 0x10;
  StatePacket out;
  EXPECT_EQ(decode_state(w, out), DecodeError::kBadChecksum);
}

TEST(RigProtocol, TruncatedAndOverlongPackets) {
  std::array<std::uint8_t, kStatePacketSize> w{};
  encode_state(StatePacket{}, w);
  StatePacket out;
  for (std::size_t n = 0; n < kStatePacketSize; ++n) {
    EXPECT_EQ(decode_state(std::span<const std::uint8_t>(w.data(), n), out), DecodeError::kTooShort)
        << n;
  }
  std::vector<std::uint8_t> longer(w.begin(), w.end());
  longer.push_back(0);
  EXPECT_EQ(decode_state(longer, out), DecodeError::kTooLong);
  std::array<std::uint8_t, kForcePacketSize> f{};
  encode_force(ForcePacket{}, f);
  ForcePacket fo;
  for (std::size_t n = 0; n < kForcePacketSize; ++n) {
    EXPECT_EQ(decode_force(std::span<const std::uint8_t>(f.data(), n), fo), DecodeError::kTooShort);
  }
}

TEST(RigProtocol, ValidChecksumButWrongTypeVersionOrLength) {
  std::array<std::uint8_t, kStatePacketSize> w{};
  const auto reseal = [&] {
    const std::uint16_t crc = crc16_ccitt(std::span<const std::uint8_t>(w.data(), 62));
    w[62] = static_cast<std::uint8_t>(crc & 0xff);
    w[63] = static_cast<std::uint8_t>(crc >> 8);
  };
  StatePacket out;
  encode_state(StatePacket{}, w);
  w[0] = kForceType;
  reseal();
  EXPECT_EQ(decode_state(w, out), DecodeError::kWrongType);
  encode_state(StatePacket{}, w);
  w[1] = 2;
  reseal();
  EXPECT_EQ(decode_state(w, out), DecodeError::kBadVersion);
  encode_state(StatePacket{}, w);
  w[2] = 63;
  reseal();
  EXPECT_EQ(decode_state(w, out), DecodeError::kLengthField);
  // A force packet is never accepted as a state packet, even padded to 64 bytes.
  std::array<std::uint8_t, kForcePacketSize> f{};
  encode_force(ForcePacket{}, f);
  EXPECT_EQ(decode_state(f, out), DecodeError::kTooShort);
}

TEST(RigProtocol, ErrorsHaveClearText) {
  for (auto e :
       {DecodeError::kOk, DecodeError::kTooShort, DecodeError::kTooLong, DecodeError::kBadChecksum,
        DecodeError::kWrongType, DecodeError::kBadVersion, DecodeError::kLengthField}) {
    EXPECT_FALSE(to_string(e).empty());
  }
  EXPECT_NE(to_string(DecodeError::kBadChecksum).find("CRC"), std::string_view::npos);
}

}  // namespace
}  // namespace serosa::haptics

// Writing and reading a block of the whole state field by field (engine/state_blocks.h).
//
// A block names its fields once, in order, in a static member
//
//   template <class S, class F> static void each(S& s, F&& f) { f(s.a); f(s.b); ... }
//
// (S is the block, const when written), and put() / get() walk that list: a bool is one byte, an
// enum its underlying integer, a number, Vec3, Mat3 or Quat its bytes, a std::array or a walked
// struct its elements in order, a std::optional a byte then its value, a vector its count then
// its elements (plain ones copied whole: they have no padding). A new field is saved the moment
// it is listed; nothing else writes or reads a block.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "engine/math.h"
#include "engine/state_codec.h"

namespace serosa {

template <class T>
concept WalkedBlock = requires(T& t) {
  T::each(t, [](auto&) {});
};

namespace walk_detail {

template <class T>
struct IsVector : std::false_type {};
template <class T, class A>
struct IsVector<std::vector<T, A>> : std::true_type {};
template <class T>
struct IsOptional : std::false_type {};
template <class T>
struct IsOptional<std::optional<T>> : std::true_type {};
template <class T>
struct IsArray : std::false_type {};
template <class T, std::size_t N>
struct IsArray<std::array<T, N>> : std::true_type {};

/// Values copied as their bytes: numbers and Eigen's fixed-size doubles (no padding, no bool).
template <class T>
inline constexpr bool kPlain =
    (std::is_arithmetic_v<T> && !std::is_same_v<T, bool>) || std::is_same_v<T, Vec3> ||
    std::is_same_v<T, Mat3> || std::is_same_v<T, Quat>;

/// Elements a vector can copy whole: plain values and arrays of them.
template <class T>
struct Packed : std::bool_constant<kPlain<T>> {};
template <class T, std::size_t N>
struct Packed<std::array<T, N>> : std::bool_constant<kPlain<T>> {};

}  // namespace walk_detail

template <class T>
void put(StateWriter& out, const T& v) {
  using namespace walk_detail;
  if constexpr (std::is_same_v<T, bool>) {
    out.u8(v ? 1 : 0);
  } else if constexpr (std::is_enum_v<T>) {
    put(out, static_cast<std::underlying_type_t<T>>(v));
  } else if constexpr (kPlain<T>) {
    out.raw(&v, sizeof v);
  } else if constexpr (std::is_same_v<T, ToolState>) {
    out.tool_state(v);
  } else if constexpr (WalkedBlock<T>) {
    T::each(v, [&](const auto& field) { put(out, field); });
  } else if constexpr (IsArray<T>::value) {
    for (const auto& e : v) put(out, e);
  } else if constexpr (IsOptional<T>::value) {
    out.u8(v ? 1 : 0);
    if (v) put(out, *v);
  } else if constexpr (IsVector<T>::value && Packed<typename T::value_type>::value) {
    out.array(v);
  } else if constexpr (IsVector<T>::value) {
    out.u64(v.size());
    for (const auto& e : v) put(out, e);
  } else {
    static_assert(sizeof(T) == 0, "a field the state walk cannot write");
  }
}

template <class T>
void get(StateReader& in, T& v) {
  using namespace walk_detail;
  if constexpr (std::is_same_v<T, bool>) {
    const std::uint8_t b = in.u8();
    if (b > 1) in.fail("a flag of " + std::to_string(b));
    v = b != 0;
  } else if constexpr (std::is_enum_v<T>) {
    std::underlying_type_t<T> u{};
    get(in, u);
    v = static_cast<T>(u);  // each block's check() rejects a value out of range
  } else if constexpr (kPlain<T>) {
    in.raw(&v, sizeof v);
  } else if constexpr (std::is_same_v<T, ToolState>) {
    v = in.tool_state();
  } else if constexpr (WalkedBlock<T>) {
    T::each(v, [&](auto& field) { get(in, field); });
  } else if constexpr (IsArray<T>::value) {
    for (auto& e : v) get(in, e);
  } else if constexpr (IsOptional<T>::value) {
    if (in.u8() != 0) {
      v.emplace();
      get(in, *v);
    } else {
      v.reset();
    }
  } else if constexpr (IsVector<T>::value && Packed<typename T::value_type>::value) {
    in.array(v);
  } else if constexpr (IsVector<T>::value) {
    const std::uint64_t n = in.u64();
    if (n > in.left()) in.fail("a list of " + std::to_string(n) + " runs past the end");
    v.clear();
    v.resize(static_cast<std::size_t>(n));
    for (auto& e : v) get(in, e);
  } else {
    static_assert(sizeof(T) == 0, "a field the state walk cannot read");
  }
}

}  // namespace serosa

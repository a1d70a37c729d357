// The whole state as bytes: SimState plus each stage's own part (a snapshot), for recordings and
// for the replay's seeks (docs/recording-format.md "Snapshots").
//
//   snapshot := "SNAP" u32:version SimState u32:blocks (string:stage_name u64:len bytes){blocks}
//   SimState := f64:time_s u64:step TetMesh u32:tools ToolState{tools} SharedState
// Integers and floats are little-endian (IEEE 754 binary64); arrays are u64:count then the
// elements' bytes. A stage's block is whatever its save() wrote (engine/stage.h); a stage that
// keeps nothing of its own writes none.
#pragma once

#include <bit>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include "engine/sim_state.h"

namespace serosa {

static_assert(std::endian::native == std::endian::little,
              "snapshots copy arrays as they lie in memory: little-endian hosts only");

/// Appends the encoding to a byte buffer.
class StateWriter {
 public:
  void u8(std::uint8_t v) { m_out.push_back(v); }
  void u32(std::uint32_t v) { raw(&v, sizeof v); }
  void u64(std::uint64_t v) { raw(&v, sizeof v); }
  void f64(double v) { raw(&v, sizeof v); }
  void string(const std::string& s);
  /// u64 count, then the elements' bytes. T: plain values WITHOUT padding (Vec3, Mat3, Quat:
  /// Eigen's fixed-size types hold just their coefficients; Tet, Tri, integers, doubles): padding
  /// bytes are indeterminate, and snapshots are compared byte for byte.
  template <class T>
  void array(const std::vector<T>& v) {
    u64(v.size());
    if (!v.empty()) raw(v.data(), v.size() * sizeof(T));
  }
  void tool_state(const ToolState& t);
  void raw(const void* p, std::size_t n);

  [[nodiscard]] std::vector<std::uint8_t>& bytes() noexcept { return m_out; }
  [[nodiscard]] std::size_t size() const noexcept { return m_out.size(); }

 private:
  std::vector<std::uint8_t> m_out;
};

/// Reads what a StateWriter wrote. Every read checks the bytes left: a short or inconsistent
/// snapshot throws InputError naming `what` and the byte offset, never reads past the end.
class StateReader {
 public:
  StateReader(std::span<const std::uint8_t> bytes, std::string what)
      : m_in(bytes), m_what(std::move(what)) {}
  std::uint8_t u8();
  std::uint32_t u32();
  std::uint64_t u64();
  double f64();
  std::string string();
  template <class T>
  void array(std::vector<T>& v) {
    const std::uint64_t n = u64();
    if (n > left() / sizeof(T))
      fail("array of " + std::to_string(n) + " elements runs past the end");
    v.resize(static_cast<std::size_t>(n));
    if (n > 0) raw(v.data(), static_cast<std::size_t>(n) * sizeof(T));
  }
  ToolState tool_state();
  void raw(void* p, std::size_t n);
  /// The next n bytes, as a view (n checked).
  std::span<const std::uint8_t> view(std::size_t n);

  [[nodiscard]] std::size_t left() const noexcept { return m_in.size() - m_pos; }
  [[nodiscard]] std::size_t offset() const noexcept { return m_pos; }
  [[nodiscard]] const std::string& what() const noexcept { return m_what; }
  /// Throws InputError(what, "byte <offset>: <message>").
  [[noreturn]] void fail(const std::string& message) const;

 private:
  std::span<const std::uint8_t> m_in;
  std::size_t m_pos = 0;
  std::string m_what;
};

/// SimState's part of a snapshot. Not written: the step's cuts (events.cuts; snapshots are
/// taken between steps with none in flight, write_sim_state throws std::logic_error otherwise)
/// and the haptic contact planes and tool reactions (events.contact_planes, tool_reactions: only
/// a live haptic loop reads them, and a replay, which restores snapshots, runs none).
void write_sim_state(StateWriter& out, const SimState& s);
/// Reads what write_sim_state wrote; checks the mesh's arrays agree in size.
[[nodiscard]] SimState read_sim_state(StateReader& in);

}  // namespace serosa

// Tool path CSV: scripted tool poses over time (docs/ARCHITECTURE.md "External contracts").
//
//   t,tool,px,py,pz,qw,qx,qy,qz,jaw
//   0.0,grasper,0.05,0.04,0.0,1,0,0,0,0.6
//
// t: time, s (finite, >= 0, non-decreasing per tool); tool: a tool name from the scene; px..pz:
// tool tip position, m; qw..qz: orientation quaternion (normalized on read; an error when its
// norm is outside [0.5, 1.5]); jaw: jaw opening angle, rad (0 = closed, 0..pi). Blank lines and
// lines starting with '#' are skipped; fields may carry surrounding spaces; CRLF is accepted.
// Rows of different tools may interleave. The header may end in ",buttons", a column of button
// masks (an integer 0..65535: bit 0 clutch, bit 1 cautery pedal, bit 2 handle button, as the rig
// reports them), held from their row to the next: how the emulated rig's handles press them.
// After it may come ",hand": the hand that holds the tool from that row on (left, right), port
// when it waits in its port out of the body, or empty when the script plays it directly
// (engine/instrument_hold.h: the upper bits of ToolState::buttons carry it).
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "engine/tool_state.h"

namespace serosa {

/// A parsed tool path: the samples of each tool, in time order.
struct ToolPath {
  std::string file;                ///< the file (or name) it was read from
  std::vector<std::string> tools;  ///< (k) tool names, in order of first appearance
  /// (k) per tool: its rows in file order (time non-decreasing), tick = 0-based row index
  std::vector<std::vector<ToolState>> samples;

  /// Index of `tool` in `tools`, or nullopt.
  [[nodiscard]] std::optional<std::size_t> index_of(std::string_view tool) const;
  /// Time of the last sample over all tools, s (0 when empty).
  [[nodiscard]] double end_time_s() const;
};

/// Reads a tool path CSV. Throws InputError naming the file and 1-based line on a missing file,
/// a wrong header, a wrong column count, a non-finite or malformed number, an empty tool name,
/// a negative time, a time going backwards for a tool, a quaternion of norm outside [0.5, 1.5],
/// a jaw angle outside [0, pi], or no rows at all.
[[nodiscard]] ToolPath read_tool_path(const std::filesystem::path& path);

/// Same on in-memory text; `name` stands for the file in errors.
[[nodiscard]] ToolPath parse_tool_path_text(const std::string& text, const std::string& name);

/// The pose of tool `tool` (index into path.tools) at time t_s: linear in position and jaw,
/// slerp (shortest arc) in orientation, clamped to the first and last samples outside their
/// time span. Where two rows share a time the pose jumps there: t at that time gives the later
/// row. Result: time_s = t_s, tick = 0-based index of the row at or before t_s, buttons those of
/// that row (0 in a file without the buttons column).
/// Throws std::out_of_range when tool is not an index of path.tools.
[[nodiscard]] ToolState sample(const ToolPath& path, std::size_t tool, double t_s);

/// Same by tool name; throws std::out_of_range when the path has no such tool.
[[nodiscard]] ToolState sample(const ToolPath& path, std::string_view tool, double t_s);

}  // namespace serosa

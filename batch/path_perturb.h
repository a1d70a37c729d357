// A perturbed copy of a tool path, for a batch's seeds: every tool's tip moved by a smooth
// random offset, the same for the same seed. Each axis of each tool's offset is a sum of three
// sines of random frequency (0.3-2 Hz, a hand's drift, not its tremor) and phase, scaled so
// that no axis moves more than `amplitude`; orientations, jaws and buttons stay as they were.
#pragma once

#include <cstdint>
#include <filesystem>

#include "engine/scene/tool_path.h"

namespace serosa::batch {

[[nodiscard]] ToolPath perturb_path(const ToolPath& path, std::uint64_t seed, double amplitude_m);

/// Writes the path as a tool path CSV (with the buttons column), full precision.
void write_tool_path(const ToolPath& path, const std::filesystem::path& file);

}  // namespace serosa::batch

// The scene a recording was made with, from its header, checked against its inputs.
#pragma once

#include <string>

#include "engine/scene/scene.h"
#include "recording/recording_reader.h"

namespace serosa::replay {

/// The scene in `rec`'s header (its text and path). Throws InputError naming `file` when the
/// header holds none or a step records another number of tools than the scene has.
[[nodiscard]] Scene recorded_scene(const recording::Recording& rec, const std::string& file);

}  // namespace serosa::replay

// Overrides of scene keys, as a batch's run or `serosa headless --set` gives them:
// "solver.tolerance=1e-4", "scene.dt=0.004", "organ.0.mesh=\"../assets/x.msh\"". The key is a
// dotted path into the scene's TOML (a number picks an element of an array of tables); the value
// is a TOML value, or a bare word where the key holds text ("solver.kind=cholmod"). A key through
// an array of tables without an index is told to name one ("organ.0.young"). A missing leaf is
// added (the loader then checks that the scene knows the key);
// a missing table on the way, or a path through a value, is an error.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "engine/scene/scene.h"

namespace serosa {

struct SceneOverride {
  std::string key;    ///< dotted path, "solver.tolerance"
  std::string value;  ///< TOML value text, "1e-4", "\"cholmod\"", "[0.0, 0.0, -9.81]"
};

/// Splits "KEY=VALUE" (the first '='); throws InputError(`where`) without one or with an empty
/// key or value.
[[nodiscard]] SceneOverride parse_override(const std::string& text, const std::string& where);

/// The scene TOML text with the overrides applied. Throws InputError naming `scene_path`, the key
/// and what is wrong (a table missing on the way, a path through a value, a value that is not
/// TOML).
[[nodiscard]] std::string apply_overrides(const std::string& toml,
                                          const std::filesystem::path& scene_path,
                                          const std::vector<SceneOverride>& overrides);

/// load_scene with the overrides applied first; errors from the loader name the overridden key
/// as any other.
[[nodiscard]] Scene load_scene(const std::filesystem::path& path,
                               const std::vector<SceneOverride>& overrides);

}  // namespace serosa

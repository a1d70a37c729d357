// What a report's numbers mean, in the report itself: the scene keys set over the file as given,
// the effective value of every material key per group and of every solver key, a hash of the
// inputs (scene text, its meshes, its tool paths) and the binary that ran them.
#pragma once

#include <vector>

#include <nlohmann/json.hpp>

#include "app/assemble_state.h"
#include "engine/scene/scene.h"
#include "engine/scene/scene_override.h"

namespace serosa::app {

/// {"overrides": [{"key", "value"}], "inputs_hash": 16 hex digits, "binary_id": 16 hex digits,
///  "materials": {GROUP: {"young_pa", "poisson", "density_kgpm3", "damping_mass_per_s",
///  "damping_stiffness_s", "plastic_yield", "plastic_creep_per_s", "plastic_max"}}}
[[nodiscard]] nlohmann::json provenance_json(const Scene& scene,
                                             const std::vector<SceneOverride>& overrides,
                                             const AssembledScene& assembled);

}  // namespace serosa::app

// Which pieces a mesh is in: nodes joined through the tets they share.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "engine/tet_mesh.h"

namespace serosa {

/// (n) the piece of each node: nodes joined through tets that `keep` accepts (every tet when it
/// is empty) share a label in [0, pieces), numbered in the order of the tets; a node in no kept
/// tet gets -1.
[[nodiscard]] std::vector<std::int32_t> node_components(
    const TetMesh& mesh, const std::function<bool(std::size_t tet)>& keep = {});

}  // namespace serosa

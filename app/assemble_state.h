// Builds the initial SimState of a scene: reads every organ's mesh, places it in the scene frame,
// gives each organ's groups scene-wide ids, marks fixed nodes and sizes the tool inputs.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "engine/io/mesh_io.h"
#include "engine/scene/scene.h"
#include "engine/sim_state.h"

namespace serosa::app {

/// What a scene-wide group id stands for.
struct GroupInfo {
  std::size_t organ = 0;  ///< index into Scene::organs
  int local_id = 0;       ///< the group id (physical tag) in the organ's mesh file
  std::string name;       ///< "appendix" (one organ) or "liver/liver" (several organs)
};

/// How many nodes of one organ each of its fixed selections picked (a node two pick counts in
/// both; `total` counts it once).
struct FixedCount {
  std::string organ;
  std::optional<std::int32_t> box;     ///< nodes in the box, when the organ gives one
  std::optional<std::int32_t> groups;  ///< nodes of the groups' tets, when it lists groups
  std::optional<std::int32_t> nodes;   ///< nodes listed by id, when it lists them
  std::int32_t total = 0;              ///< fixed nodes of the organ
};

struct AssembledScene {
  SimState state;                     ///< all organs in one TetMesh, tools at rest
  std::vector<FixedCount> fixed;      ///< per organ, scene order
  std::map<int, GroupInfo> groups;    ///< scene-wide group id -> origin
  std::vector<MeshReadReport> reads;  ///< (organs) what each mesh read reported

  /// Scene-wide group id -> name, for OBJ groups and Gmsh $PhysicalNames.
  [[nodiscard]] std::map<int, std::string> group_names() const;
  /// The material of the tets of scene-wide group g.
  [[nodiscard]] const Material& material(const Scene& scene, int g) const;
};

/// Reads the organs' meshes (InputError naming the mesh file on bad input), applies each organ's
/// transform to rest and current positions, and fixes the nodes its FixedSpec selects. A single
/// organ keeps its mesh's group ids; with several, organ k's groups are shifted past those of
/// organs 0..k-1 so that ids stay unique.
[[nodiscard]] AssembledScene assemble_state(const Scene& scene);

}  // namespace serosa::app

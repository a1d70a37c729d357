// A mesh file read and checked (engine/mesh_check.h) with its pieces per group, and the JSON
// object `serosa check --json` prints (docs/ARCHITECTURE.md "External contracts"); the Python
// module's check_mesh returns the same object.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "engine/io/mesh_io.h"
#include "engine/mesh_check.h"
#include "engine/tet_mesh.h"

namespace serosa::app {

/// Pieces per group: tets connected through shared nodes (a transected organ part has two).
using Pieces = std::map<int, std::int32_t>;

struct CheckedMesh {
  TetMesh mesh;
  MeshReadReport read;     ///< what the reader reported (format, groups' names, lines)
  MeshCheckReport report;  ///< counts, volumes, quality, invariants
  Pieces pieces;
};

/// Reads `path` (repairing inverted tets when asked) and checks it. InputError naming the file
/// and line when it does not read.
[[nodiscard]] CheckedMesh check_mesh_file(const std::filesystem::path& path,
                                          bool repair_inverted = false);

/// The check as `serosa check --json` prints it; `file` as the user named it.
[[nodiscard]] nlohmann::json check_json(const std::string& file, const CheckedMesh& checked);

}  // namespace serosa::app

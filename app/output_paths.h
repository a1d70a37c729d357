// The command line's output files, checked before the first step (a long run must not end on a
// typo): a file's folder must exist (never created silently), a folder output may be created in
// an existing parent, and a mesh's format follows its name's extension or is refused. Each error
// is an InputError naming the option and the path.
#pragma once

#include <filesystem>
#include <map>
#include <string>

#include "engine/tet_mesh.h"

namespace serosa::app {

enum class MeshOutputFormat { kGmsh22, kVtu, kObj };

/// The format `path`'s extension names: .msh (Gmsh 2.2), .vtu (VTK XML, ParaView), .obj (the
/// boundary surface); any other is refused, naming `option`.
[[nodiscard]] MeshOutputFormat mesh_output_format(const std::string& option,
                                                  const std::filesystem::path& path);

/// A file the run will write: not a folder, in a folder that exists.
void check_output_file(const std::string& option, const std::filesystem::path& path);

/// A folder the run will write into: a folder if it exists, else its parent exists.
void check_output_folder(const std::string& option, const std::filesystem::path& path);

/// Writes the mesh in `format` (OBJ: its boundary surface), at its current positions or, with
/// `current` false, at its rest positions.
void write_mesh_output(const std::filesystem::path& path, MeshOutputFormat format,
                       const TetMesh& mesh, const std::map<int, std::string>& group_names,
                       bool current = true);

}  // namespace serosa::app

#include "app/output_paths.h"

#include "engine/input_error.h"
#include "engine/io/mesh_io.h"
#include "surface/extract_surface.h"

namespace serosa::app {

namespace fs = std::filesystem;

MeshOutputFormat mesh_output_format(const std::string& option, const fs::path& path) {
  const std::string ext = path.extension().string();
  if (ext == ".msh") return MeshOutputFormat::kGmsh22;
  if (ext == ".vtu") return MeshOutputFormat::kVtu;
  if (ext == ".obj") return MeshOutputFormat::kObj;
  throw InputError(option + " " + path.string(), 0,
                   ext.empty() ? "no extension to tell the format by"
                               : "'" + ext + "' is not a mesh format serosa writes",
                   ".msh (Gmsh 2.2), .vtu (VTK XML, ParaView) or .obj (the boundary surface)");
}

void check_output_file(const std::string& option, const fs::path& path) {
  std::error_code ec;
  if (fs::is_directory(path, ec))
    throw InputError(option + " " + path.string(), 0, "is a folder", "a file path");
  const fs::path parent = path.has_parent_path() ? path.parent_path() : fs::path(".");
  if (!fs::is_directory(parent, ec))
    throw InputError(option + " " + path.string(), 0,
                     "its folder " + parent.string() + " does not exist",
                     "a path in an existing folder");
}

void check_output_folder(const std::string& option, const fs::path& path) {
  std::error_code ec;
  if (fs::exists(path, ec)) {
    if (!fs::is_directory(path, ec))
      throw InputError(option + " " + path.string(), 0, "is a file", "a folder");
    return;
  }
  const fs::path parent = path.has_parent_path() ? path.parent_path() : fs::path(".");
  if (!fs::is_directory(parent, ec))
    throw InputError(option + " " + path.string(), 0,
                     "its parent folder " + parent.string() + " does not exist",
                     "a folder in an existing one");
}

void write_mesh_output(const fs::path& path, MeshOutputFormat format, const TetMesh& mesh,
                       const std::map<int, std::string>& group_names, bool current) {
  const bool has_x = mesh.x.size() == mesh.rest.size();
  switch (format) {
    case MeshOutputFormat::kGmsh22:
      write_gmsh22(path, mesh, current && has_x, group_names);
      return;
    case MeshOutputFormat::kVtu: {
      if (current || !has_x) {
        write_vtu(path, mesh);  // its points: x, else rest
        return;
      }
      TetMesh at_rest = mesh;
      at_rest.x = at_rest.rest;
      write_vtu(path, at_rest);
      return;
    }
    case MeshOutputFormat::kObj: {
      const SurfaceMesh s = surface::extract_surface(mesh);
      write_obj(path, current && has_x ? mesh.x : mesh.rest, s.faces, s.face_group, group_names);
      return;
    }
  }
}

}  // namespace serosa::app

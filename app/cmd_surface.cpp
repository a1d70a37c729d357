// serosa surface MESH --out OUT.obj: the boundary surface of a tet mesh as OBJ, one OBJ group per
// mesh group (named from Gmsh $PhysicalNames when the file has them), faces oriented outward
// (docs/ARCHITECTURE.md "External contracts"). Refuses (exit 1) a mesh whose faces are shared by
// more than two tets or that check_mesh finds invalid otherwise: its "surface" would not bound a
// solid.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "app/command.h"
#include "engine/boundary.h"
#include "engine/input_error.h"
#include "engine/io/mesh_io.h"
#include "engine/mesh_check.h"

namespace serosa::app {

namespace {

struct SurfaceArgs {
  std::string mesh;  // path of the input mesh
  std::string out;   // path of the OBJ to write
};

int run_surface(const SurfaceArgs& args) {
  std::error_code ec;
  if (!std::filesystem::exists(args.mesh, ec)) {
    throw InputError(args.mesh, 0, "no such file", "an existing mesh file");
  }
  MeshReadReport read;
  const TetMesh mesh = read_mesh(args.mesh, {}, &read);
  const MeshCheckReport check = check_mesh(mesh);
  if (!check.valid) {
    for (const auto& p : check.problems) {
      std::fprintf(stderr, "error: %s: %s\n", args.mesh.c_str(), p.c_str());
    }
    std::fprintf(stderr, "error: %s: invalid mesh, no surface written\n", args.mesh.c_str());
    return 1;
  }

  const FaceCensus census = face_census(mesh);
  std::vector<Tri> faces;                 // (f) outward-wound node ids
  std::vector<std::uint16_t> face_group;  // (f) group of each face's tet
  faces.reserve(census.boundary.size());
  face_group.reserve(census.boundary.size());
  std::set<std::uint16_t> groups;
  for (const BoundaryFace& f : census.boundary) {
    faces.push_back(f.nodes);
    face_group.push_back(f.group);
    groups.insert(f.group);
  }
  write_obj(args.out, mesh.rest, faces, face_group, read.group_names);
  std::printf("surface: %zu boundary faces in %zu groups over %d nodes -> %s\n", faces.size(),
              groups.size(), mesh.num_nodes(), args.out.c_str());
  return 0;
}

}  // namespace

void add_surface_command(CLI::App& app, Action& action) {
  auto args = std::make_shared<SurfaceArgs>();
  CLI::App* cmd =
      app.add_subcommand("surface", "Write a tet mesh's boundary surface as OBJ (outward faces)");
  cmd->add_option("mesh", args->mesh, "Mesh file (.msh Gmsh 2.2/4.1, .node/.ele TetGen, .vtk)")
      ->required();
  cmd->add_option("--out", args->out, "OBJ file to write")->required();
  cmd->callback([&action, args] { action = [args] { return run_surface(*args); }; });
}

}  // namespace serosa::app

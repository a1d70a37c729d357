#include "app/render_frame_from_surface.h"

#include <algorithm>
#include <array>

#include "render/vertex_normals.h"

namespace serosa::app {

void fill_render_frame(const TetMesh& mesh, const surface::SurfaceMesh& surface,
                       const std::map<int, std::string>& group_names, bool with_edges,
                       render::RenderFrame& frame) {
  const std::size_t n = mesh.x.size();
  frame.pos.resize(3 * n);
  for (std::size_t i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) frame.pos[3 * i + k] = static_cast<float>(mesh.x[i][k]);

  const std::size_t f = surface.faces.size();
  frame.tri.resize(3 * f);
  for (std::size_t i = 0; i < f; ++i)
    for (int k = 0; k < 3; ++k)
      frame.tri[3 * i + k] = static_cast<std::uint32_t>(surface.faces[i][k]);
  frame.tri_group = surface.face_group;
  frame.tri_cut.assign(f, 0);
  // Tet edges change only with the topology: keep them across frames otherwise.
  const bool edges_stale =
      frame.edges.empty() || frame.topology_version != surface.topology_version;
  frame.topology_version = surface.topology_version;

  frame.group_names.clear();
  if (!group_names.empty()) {
    frame.group_names.resize(static_cast<std::size_t>(group_names.rbegin()->first) + 1);
    for (const auto& [id, name] : group_names)
      if (id >= 0) frame.group_names[static_cast<std::size_t>(id)] = name;
  }

  if (!with_edges) frame.edges.clear();
  if (with_edges && edges_stale) {
    frame.edges.clear();
    // Unique tet edges, sorted.
    std::vector<std::array<std::uint32_t, 2>> e;
    e.reserve(6 * mesh.tets.size());
    for (const Tet& t : mesh.tets)
      for (int a = 0; a < 4; ++a)
        for (int b = a + 1; b < 4; ++b) {
          auto u = static_cast<std::uint32_t>(t[a]), v = static_cast<std::uint32_t>(t[b]);
          e.push_back({std::min(u, v), std::max(u, v)});
        }
    std::sort(e.begin(), e.end());
    e.erase(std::unique(e.begin(), e.end()), e.end());
    frame.edges.reserve(2 * e.size());
    for (const auto& [u, v] : e) {
      frame.edges.push_back(u);
      frame.edges.push_back(v);
    }
  }
  frame.nrm = render::compute_vertex_normals(frame.pos, frame.tri);
}

}  // namespace serosa::app

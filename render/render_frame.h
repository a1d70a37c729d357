// RenderFrame: the plain data the renderer draws (shared/STYLE.md "render/": a render stage fills
// plain data with no GL; drawing is separate). No GL handles, no pointers into simulation state.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace serosa::render {

/// A pinhole camera in world coordinates (m). The light sits at the eye (an endoscope's tip).
struct Camera {
  std::array<float, 3> eye{0.0f, 0.0f, 1.0f};     ///< camera position, m
  std::array<float, 3> target{0.0f, 0.0f, 0.0f};  ///< point looked at, m
  std::array<float, 3> up{0.0f, 1.0f, 0.0f};      ///< approximate up direction (need not be unit)
  float fov_y_deg = 70.0f;                        ///< vertical field of view, degrees
};

/// One frame to draw: the organs' boundary surface (and optionally the tet edges), the camera.
///
/// Shapes: n vertices, t triangles, e edges. `pos` may hold more vertices than the triangles use
/// (all tet nodes, say, so that `edges` can index interior nodes); unused vertices are not drawn
/// in the visual and collision views.
struct RenderFrame {
  std::vector<float> pos;          ///< (n x 3) vertex positions, m
  std::vector<float> nrm;          ///< (n x 3) unit normals; empty: computed when drawn
  std::vector<std::uint32_t> tri;  ///< (t x 3) vertex ids, counter-clockwise seen from outside
  std::vector<std::uint16_t> tri_group;  ///< (t) visual group (Gmsh physical tag) of each triangle
  std::vector<std::uint8_t> tri_cut;     ///< (t) 1 = face made by a cut (wound), else 0
  /// (e x 2) vertex ids of the tet edges, for the mechanical view. Optional: when empty, the
  /// mechanical view draws the triangles' edges instead.
  std::vector<std::uint32_t> edges;
  /// Optional names of the groups, indexed by group id ("appendix", "mesoappendix", "cecum",
  /// "liver", ...): a known name picks its material, anything else a palette colour by id.
  std::vector<std::string> group_names;
  /// The mesh's topology version: a FrameRenderer re-uploads indices and per-triangle materials
  /// only when it (or the triangle or edge count) changes; bump it whenever tri, tri_group,
  /// tri_cut, edges or group_names change.
  std::uint64_t topology_version = 0;
  Camera camera;

  [[nodiscard]] std::size_t num_vertices() const { return pos.size() / 3; }
  [[nodiscard]] std::size_t num_triangles() const { return tri.size() / 3; }
};

/// Checks shapes and ids: pos a multiple of 3; nrm empty or as long as pos; tri a multiple of 3
/// with ids < n; tri_group and tri_cut empty or one per triangle; edges a multiple of 2 with ids
/// < n. Returns one message per problem; empty == valid.
[[nodiscard]] std::vector<std::string> validate(const RenderFrame& frame);

}  // namespace serosa::render

// Meshes and image statistics shared by the render tests: icospheres, a tet fan, masks.
#pragma once

#include <dlfcn.h>
#include <link.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "render/icosphere.h"
#include "render/image.h"
#include "render/render_frame.h"
#include "render/vertex_normals.h"
#include "support/test_paths.h"

namespace serosa::render::fixtures {

/// A surface mesh: (n x 3) positions, m, and (t x 3) counter-clockwise (outward) triangles.
struct Surface {
  std::vector<float> pos;
  std::vector<std::uint32_t> tri;
};

/// The regular icosahedron inscribed in the sphere of `radius` m at the origin (12 vertices,
/// 20 outward faces): render/icosphere.h.
inline Surface icosahedron(float radius = 1.0f) {
  TriMesh m = ::serosa::render::icosahedron(radius);
  return {std::move(m.pos), std::move(m.tri)};
}

/// An icosphere (20 * 4^levels triangles on the sphere of `radius` m): render/icosphere.h.
inline Surface icosphere(int levels, float radius = 1.0f) {
  TriMesh m = ::serosa::render::icosphere(levels, radius);
  return {std::move(m.pos), std::move(m.tri)};
}

/// A frame of `s` with area-weighted normals, every triangle in `group`, no wound, a camera on
/// the +z axis at `distance` m looking at the origin with a 40 degree field of view.
inline RenderFrame frame_of(const Surface& s, std::uint16_t group = 1, float distance = 4.0f) {
  RenderFrame f;
  f.pos = s.pos;
  f.tri = s.tri;
  f.nrm = compute_vertex_normals(f.pos, f.tri);
  f.tri_group.assign(f.num_triangles(), group);
  f.tri_cut.assign(f.num_triangles(), 0);
  f.camera.eye = {0.0f, 0.0f, distance};
  f.camera.target = {0.0f, 0.0f, 0.0f};
  f.camera.up = {0.0f, 1.0f, 0.0f};
  f.camera.fov_y_deg = 40.0f;
  return f;
}

/// Adds a centre node to the frame and the edges of the tet fan it makes with the surface (each
/// surface edge and each spoke from the centre): a stand-in for a tet mesh's edges.
inline void add_tet_fan_edges(RenderFrame& f) {
  const auto centre = static_cast<std::uint32_t>(f.num_vertices());
  f.pos.insert(f.pos.end(), {0.0f, 0.0f, 0.0f});
  f.nrm.insert(f.nrm.end(), {0.0f, 0.0f, 0.0f});
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> seen;
  for (std::size_t t = 0; t < f.tri.size(); t += 3) {
    for (std::size_t k = 0; k < 3; ++k) {
      const auto e = std::minmax(f.tri[t + k], f.tri[t + (k + 1) % 3]);
      if (seen.emplace(e, 0).second) f.edges.insert(f.edges.end(), {e.first, e.second});
    }
  }
  for (std::uint32_t v = 0; v < centre; ++v) f.edges.insert(f.edges.end(), {centre, v});
}

/// Coverage mask: 1 where alpha >= 128 (a surface or line covers at least half the pixel).
inline std::vector<std::uint8_t> coverage(const Image& img) {
  std::vector<std::uint8_t> m(static_cast<std::size_t>(img.width) * img.height);
  for (std::size_t i = 0; i < m.size(); ++i) m[i] = img.rgba[4 * i + 3] >= 128 ? 1 : 0;
  return m;
}

inline double coverage_fraction(const Image& img) {
  const auto m = coverage(img);
  std::size_t n = 0;
  for (const auto v : m) n += v;
  return static_cast<double>(n) / static_cast<double>(m.size());
}

/// Number of pixels where two masks differ.
inline std::size_t mask_difference(const std::vector<std::uint8_t>& a,
                                   const std::vector<std::uint8_t>& b) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < a.size() && i < b.size(); ++i) n += a[i] != b[i] ? 1 : 0;
  return n;
}

/// Number of covered pixels (alpha >= 128) whose RGB satisfies `pred`.
inline std::size_t count_pixels(const Image& img,
                                const std::function<bool(int r, int g, int b)>& pred) {
  std::size_t n = 0;
  for (std::size_t i = 0; i + 3 < img.rgba.size(); i += 4) {
    if (img.rgba[i + 3] >= 128 && pred(img.rgba[i], img.rgba[i + 1], img.rgba[i + 2])) ++n;
  }
  return n;
}

/// Mean RGB over covered pixels (0..255 each); zeros when nothing is covered.
inline std::array<double, 3> mean_covered_rgb(const Image& img) {
  std::array<double, 3> sum{};
  std::size_t n = 0;
  for (std::size_t i = 0; i + 3 < img.rgba.size(); i += 4) {
    if (img.rgba[i + 3] < 128) continue;
    for (std::size_t k = 0; k < 3; ++k) sum[k] += img.rgba[i + k];
    ++n;
  }
  if (n > 0) {
    for (double& s : sum) s /= static_cast<double>(n);
  }
  return sum;
}

/// The wound's look: a dark, saturated red (green and blue well below red).
inline bool is_wound_red(int r, int g, int b) {
  return r >= 40 && g * 10 < r * 3 && b * 10 < r * 3;
}

/// Keeps the loaded Mesa DRI driver (*_dri.so, libgallium*) in memory for the rest of the
/// process. Mesa dlopens the driver in eglInitialize and dlcloses it in eglTerminate; the driver's
/// global caches (allocated while compiling shaders) then lose their only references, and
/// LeakSanitizer reports them at exit as leaks from "<unknown module>", which no suppression can
/// name. Pinned, they stay reachable and real leaks in our code still show. Tests only.
inline void pin_gl_driver() {
  std::vector<std::string> names;
  dl_iterate_phdr(
      [](dl_phdr_info* info, std::size_t, void* data) {
        const std::string name = info->dlpi_name != nullptr ? info->dlpi_name : "";
        if (name.find("_dri.so") != std::string::npos ||
            name.find("libgallium") != std::string::npos) {
          static_cast<std::vector<std::string>*>(data)->push_back(name);
        }
        return 0;
      },
      &names);
  // RTLD_NOLOAD: only if already loaded; RTLD_NODELETE: never unload it.
  for (const std::string& n : names) dlopen(n.c_str(), RTLD_NOW | RTLD_NOLOAD | RTLD_NODELETE);
}

/// Where test pictures go so that a person can look at them.
inline std::string output_path(const std::string& name) {
  return std::string(::serosa::test_paths::binary_dir()) + "/test-output/render/" + name;
}

}  // namespace serosa::render::fixtures

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

#include "render/image.h"
#include "render/render_frame.h"
#include "render/vertex_normals.h"

namespace serosa::render::fixtures {

/// A surface mesh: (n x 3) positions, m, and (t x 3) counter-clockwise (outward) triangles.
struct Surface {
  std::vector<float> pos;
  std::vector<std::uint32_t> tri;
};

/// The regular icosahedron inscribed in the sphere of `radius` m at the origin (12 vertices,
/// 20 outward faces).
inline Surface icosahedron(float radius = 1.0f) {
  const float p = (1.0f + std::sqrt(5.0f)) / 2.0f;
  const std::array<std::array<float, 3>, 12> v{{{-1, p, 0},
                                                {1, p, 0},
                                                {-1, -p, 0},
                                                {1, -p, 0},
                                                {0, -1, p},
                                                {0, 1, p},
                                                {0, -1, -p},
                                                {0, 1, -p},
                                                {p, 0, -1},
                                                {p, 0, 1},
                                                {-p, 0, -1},
                                                {-p, 0, 1}}};
  Surface s;
  for (const auto& q : v) {
    const float len = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
    for (const float c : q) s.pos.push_back(radius * c / len);
  }
  s.tri = {0, 11, 5,  0, 5,  1, 0, 1, 7, 0, 7,  10, 0, 10, 11, 1, 5, 9, 5, 11,
           4, 11, 10, 2, 10, 7, 6, 7, 1, 8, 3,  9,  4, 3,  4,  2, 3, 2, 6, 3,
           6, 8,  3,  8, 9,  4, 9, 5, 2, 4, 11, 6,  2, 10, 8,  6, 7, 9, 8, 1};
  return s;
}

/// An icosphere: the icosahedron with every triangle split into 4, `levels` times, vertices pushed
/// onto the sphere of `radius` m (20 * 4^levels triangles).
inline Surface icosphere(int levels, float radius = 1.0f) {
  Surface s = icosahedron(radius);
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> mid;
    const auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
      const auto key = std::minmax(a, b);
      const auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      std::array<float, 3> m{};
      for (int k = 0; k < 3; ++k) m[k] = 0.5f * (s.pos[3 * a + k] + s.pos[3 * b + k]);
      const float len = std::sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]);
      const auto id = static_cast<std::uint32_t>(s.pos.size() / 3);
      for (const float c : m) s.pos.push_back(radius * c / len);
      mid.emplace(key, id);
      return id;
    };
    std::vector<std::uint32_t> next;
    for (std::size_t f = 0; f < s.tri.size(); f += 3) {
      const std::uint32_t a = s.tri[f], b = s.tri[f + 1], c = s.tri[f + 2];
      const std::uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      next.insert(next.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
    }
    s.tri = std::move(next);
  }
  return s;
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
  return std::string(SEROSA_BINARY_DIR) + "/test-output/render/" + name;
}

}  // namespace serosa::render::fixtures

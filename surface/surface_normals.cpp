#include "surface/surface_normals.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>
#include <tuple>

namespace serosa::surface {
namespace {

// Union-find over the 3 f corners (corner = 3 face + k).
class Dsu {
 public:
  explicit Dsu(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }
  std::int64_t find(std::int64_t a) {
    while (parent_[static_cast<std::size_t>(a)] != a) {
      auto& p = parent_[static_cast<std::size_t>(a)];
      p = parent_[static_cast<std::size_t>(p)];  // path halving
      a = p;
    }
    return a;
  }
  void unite(std::int64_t a, std::int64_t b) {
    a = find(a);
    b = find(b);
    if (a == b) return;
    if (b < a) std::swap(a, b);
    parent_[static_cast<std::size_t>(b)] = a;  // the smaller corner is the root
  }

 private:
  std::vector<std::int64_t> parent_;
};

}  // namespace

void compute_render_vertices(const SurfaceMesh& s, std::span<const Vec3> x,
                             const NormalOptions& options, RenderVertices& out) {
  const std::size_t f = s.faces.size();
  if (s.face_cut.size() != f || s.face_group.size() != f)
    throw std::invalid_argument("compute_render_vertices: face_cut or face_group not sized (f)");
  for (std::size_t i = 0; i < f; ++i)
    for (std::int32_t v : s.faces[i])
      if (v < 0 || static_cast<std::size_t>(v) >= x.size())
        throw std::invalid_argument("compute_render_vertices: face " + std::to_string(i) +
                                    " names node " + std::to_string(v) + ", outside x");
  out.node.clear();
  out.normal.clear();
  out.tris.assign(f, Tri{});
  if (f == 0) return;

  // 1. Area-weighted face normals (|n| = twice the area) and unit ones for the crease test.
  std::vector<Vec3> area_n(f);
  std::vector<Vec3> unit_n(f);
  for (std::size_t i = 0; i < f; ++i) {
    const Tri& t = s.faces[i];
    const Vec3& a = x[static_cast<std::size_t>(t[0])];
    area_n[i] =
        (x[static_cast<std::size_t>(t[1])] - a).cross(x[static_cast<std::size_t>(t[2])] - a);
    const double len = area_n[i].norm();
    unit_n[i] = len > 0.0 ? Vec3(area_n[i] / len) : Vec3::Zero();
  }

  // 2. Edges: (low node, high node, face, local corner of the low node, of the high node).
  struct EdgeUse {
    std::int32_t lo, hi, face;
    std::int8_t klo, khi;
  };
  std::vector<EdgeUse> uses;
  uses.reserve(3 * f);
  for (std::size_t i = 0; i < f; ++i)
    for (std::int8_t k = 0; k < 3; ++k) {
      const auto k1 = static_cast<std::int8_t>((k + 1) % 3);
      std::int32_t a = s.faces[i][static_cast<std::size_t>(k)];
      std::int32_t b = s.faces[i][static_cast<std::size_t>(k1)];
      std::int8_t ka = k, kb = k1;
      if (b < a) {
        std::swap(a, b);
        std::swap(ka, kb);
      }
      uses.push_back(EdgeUse{a, b, static_cast<std::int32_t>(i), ka, kb});
    }
  std::sort(uses.begin(), uses.end(), [](const EdgeUse& p, const EdgeUse& q) {
    return std::tie(p.lo, p.hi, p.face) < std::tie(q.lo, q.hi, q.face);
  });

  // 3. Join the corners across each smooth manifold edge.
  const double cos_crease = std::cos(options.crease_angle_rad);
  Dsu dsu(3 * f);
  for (std::size_t i = 0; i < uses.size();) {
    std::size_t j = i;
    while (j < uses.size() && uses[j].lo == uses[i].lo && uses[j].hi == uses[i].hi) ++j;
    if (j - i == 2) {
      const EdgeUse& p = uses[i];
      const EdgeUse& q = uses[i + 1];
      const auto fp = static_cast<std::size_t>(p.face), fq = static_cast<std::size_t>(q.face);
      const bool smooth = unit_n[fp].dot(unit_n[fq]) >= cos_crease &&
                          !(options.split_cut_edges && s.face_cut[fp] != s.face_cut[fq]) &&
                          !(options.split_groups && s.face_group[fp] != s.face_group[fq]);
      if (smooth) {
        dsu.unite(3 * std::int64_t{p.face} + p.klo, 3 * std::int64_t{q.face} + q.klo);
        dsu.unite(3 * std::int64_t{p.face} + p.khi, 3 * std::int64_t{q.face} + q.khi);
      }
    }
    i = j;
  }

  // 4. One render vertex per cluster root, ordered by (node, root corner).
  std::vector<std::pair<std::int32_t, std::int64_t>> roots;  // (node, root corner)
  for (std::size_t c = 0; c < 3 * f; ++c)
    if (dsu.find(static_cast<std::int64_t>(c)) == static_cast<std::int64_t>(c))
      roots.emplace_back(s.faces[c / 3][c % 3], static_cast<std::int64_t>(c));
  std::sort(roots.begin(), roots.end());
  std::vector<std::int32_t> vertex_of_root(3 * f, -1);
  out.node.resize(roots.size());
  out.normal.assign(roots.size(), Vec3::Zero());
  for (std::size_t v = 0; v < roots.size(); ++v) {
    out.node[v] = roots[v].first;
    vertex_of_root[static_cast<std::size_t>(roots[v].second)] = static_cast<std::int32_t>(v);
  }
  for (std::size_t c = 0; c < 3 * f; ++c) {
    const std::int32_t v =
        vertex_of_root[static_cast<std::size_t>(dsu.find(static_cast<std::int64_t>(c)))];
    out.tris[c / 3][c % 3] = v;
    out.normal[static_cast<std::size_t>(v)] += area_n[c / 3];
  }

  // 5. Normalise; zero-area clusters fall back to the node's whole fan, then +z.
  std::vector<Vec3> fan;  // per node, only filled when needed
  for (std::size_t v = 0; v < out.node.size(); ++v) {
    const double len = out.normal[v].norm();
    if (len > 0.0) {
      out.normal[v] /= len;
      continue;
    }
    if (fan.empty()) {
      fan.assign(x.size(), Vec3::Zero());
      for (std::size_t i = 0; i < f; ++i)
        for (std::int32_t n : s.faces[i]) fan[static_cast<std::size_t>(n)] += area_n[i];
    }
    const Vec3& w = fan[static_cast<std::size_t>(out.node[v])];
    out.normal[v] = w.norm() > 0.0 ? Vec3(w.normalized()) : Vec3::UnitZ();
  }
}

}  // namespace serosa::surface

#include "cutting/tet_bvh.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>

namespace serosa::cutting {
namespace {

constexpr std::int32_t kLeafSize = 4;

void tet_bounds(const TetMesh& m, std::int32_t ti, Vec3& lo, Vec3& hi) {
  const Tet& t = m.tets[ti];
  lo = hi = m.x[t[0]];
  for (int k = 1; k < 4; ++k) {
    lo = lo.cwiseMin(m.x[t[k]]);
    hi = hi.cwiseMax(m.x[t[k]]);
  }
}

}  // namespace

TetBvh::TetBvh(const TetMesh& mesh) {
  const std::int32_t m = mesh.num_tets();
  m_order.resize(static_cast<std::size_t>(m));
  std::iota(m_order.begin(), m_order.end(), 0);
  std::vector<Vec3> centroids(static_cast<std::size_t>(m));
  for (std::int32_t i = 0; i < m; ++i) {
    const Tet& t = mesh.tets[i];
    centroids[i] = (mesh.x[t[0]] + mesh.x[t[1]] + mesh.x[t[2]] + mesh.x[t[3]]) / 4.0;
  }
  if (m > 0) build(mesh, centroids, 0, m);
  m_lo.resize(m_order.size());
  m_hi.resize(m_order.size());
  for (std::size_t i = 0; i < m_order.size(); ++i) tet_bounds(mesh, m_order[i], m_lo[i], m_hi[i]);
}

std::int32_t TetBvh::build(const TetMesh& mesh, std::vector<Vec3>& centroids, std::int32_t begin,
                           std::int32_t end) {
  const auto id = static_cast<std::int32_t>(m_nodes.size());
  m_nodes.emplace_back();
  Vec3 lo, hi, clo, chi;
  tet_bounds(mesh, m_order[begin], lo, hi);
  clo = chi = centroids[m_order[begin]];
  for (std::int32_t i = begin; i < end; ++i) {
    Vec3 a, b;
    tet_bounds(mesh, m_order[i], a, b);
    lo = lo.cwiseMin(a);
    hi = hi.cwiseMax(b);
    clo = clo.cwiseMin(centroids[m_order[i]]);
    chi = chi.cwiseMax(centroids[m_order[i]]);
  }
  m_nodes[id].lo = lo;
  m_nodes[id].hi = hi;
  if (end - begin <= kLeafSize) {
    m_nodes[id].first = begin;
    m_nodes[id].count = end - begin;
    return id;
  }
  int axis = 0;
  (chi - clo).maxCoeff(&axis);
  const std::int32_t mid = begin + (end - begin) / 2;
  std::nth_element(m_order.begin() + begin, m_order.begin() + mid, m_order.begin() + end,
                   [&](std::int32_t a, std::int32_t b) {
                     return centroids[a][axis] < centroids[b][axis] ||
                            (centroids[a][axis] == centroids[b][axis] && a < b);
                   });
  const std::int32_t left = build(mesh, centroids, begin, mid);
  const std::int32_t right = build(mesh, centroids, mid, end);
  m_nodes[id].first = left;
  m_nodes[id].right = right;
  m_nodes[id].count = 0;
  return id;
}

void TetBvh::refit(const TetMesh& mesh) {
  if (mesh.num_tets() != num_tets())
    throw std::invalid_argument("TetBvh::refit: the mesh has " + std::to_string(mesh.num_tets()) +
                                " tets, the BVH " + std::to_string(num_tets()) +
                                " (topology changed: rebuild)");
  for (std::size_t k = m_nodes.size(); k-- > 0;) {  // children come after their parent
    Node& n = m_nodes[k];
    if (n.count > 0) {
      for (std::int32_t i = n.first; i < n.first + n.count; ++i) {
        tet_bounds(mesh, m_order[i], m_lo[i], m_hi[i]);
        n.lo = i == n.first ? m_lo[i] : Vec3(n.lo.cwiseMin(m_lo[i]));
        n.hi = i == n.first ? m_hi[i] : Vec3(n.hi.cwiseMax(m_hi[i]));
      }
    } else {
      n.lo = m_nodes[n.first].lo.cwiseMin(m_nodes[n.right].lo);
      n.hi = m_nodes[n.first].hi.cwiseMax(m_nodes[n.right].hi);
    }
  }
}

void TetBvh::query(const Vec3& lo, const Vec3& hi, std::vector<std::int32_t>& out) const {
  if (m_nodes.empty()) return;
  std::vector<std::int32_t> stack{0};
  while (!stack.empty()) {
    const Node& n = m_nodes[stack.back()];
    stack.pop_back();
    if (!((n.lo.array() <= hi.array()).all() && (n.hi.array() >= lo.array()).all())) continue;
    if (n.count > 0) {
      for (std::int32_t i = n.first; i < n.first + n.count; ++i)
        if ((m_lo[i].array() <= hi.array()).all() && (m_hi[i].array() >= lo.array()).all())
          out.push_back(m_order[i]);
    } else {
      stack.push_back(n.first);
      stack.push_back(n.right);
    }
  }
}

TetBoxQuery TetBvh::as_query() const {
  return [this](const Vec3& lo, const Vec3& hi, std::vector<std::int32_t>& out) {
    query(lo, hi, out);
  };
}

}  // namespace serosa::cutting

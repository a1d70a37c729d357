#include "cutting/tet_bvh.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <stdexcept>
#include <string>

#include "engine/geometry/tet_extent.h"

namespace serosa::cutting {
namespace {

constexpr std::size_t kLeafSize = 4;
constexpr std::size_t kMaxLeaf = 8;

Vec3 centroid(const TetMesh& m, std::int32_t ti) {
  const Tet& t = m.tets[ti];
  return (m.x[t[0]] + m.x[t[1]] + m.x[t[2]] + m.x[t[3]]) / 4.0;
}

double half_area(const Vec3& lo, const Vec3& hi) {
  const Vec3 d = (hi - lo).cwiseMax(Vec3::Zero());
  return d.x() * d.y() + d.y() * d.z() + d.z() * d.x();
}

// Nodes build() makes for `count` tets (median splits down to kLeafSize): 1 + both halves. Sizes
// on one level differ by at most one, so memoising keeps this O(log count).
std::size_t build_node_count(std::size_t count, std::map<std::size_t, std::size_t>& memo) {
  if (count <= kLeafSize) return 1;
  if (const auto it = memo.find(count); it != memo.end()) return it->second;
  const std::size_t n =
      1 + build_node_count(count / 2, memo) + build_node_count(count - count / 2, memo);
  memo.emplace(count, n);
  return n;
}

const Vec3 kEmptyLo = Vec3::Constant(std::numeric_limits<double>::infinity());
const Vec3 kEmptyHi = Vec3::Constant(-std::numeric_limits<double>::infinity());

}  // namespace

TetBvh::TetBvh(const TetMesh& mesh, double spare) : m_spare(spare) {
  if (!std::isfinite(spare) || spare < 0.0) {
    std::string what = "TetBvh: spare must be finite and >= 0, got ";
    what.append(std::to_string(spare));
    throw std::invalid_argument(what);
  }
  const std::int32_t m = mesh.num_tets();
  // Spare capacity for the tets and nodes cuts append (update()): without it the first cut
  // after a build reallocates every array, O(m).
  const auto with_spare = [spare](std::size_t count) {
    return static_cast<std::size_t>(std::ceil(static_cast<double>(count) * (1.0 + spare)));
  };
  m_lo.reserve(with_spare(static_cast<std::size_t>(m)));
  m_hi.reserve(with_spare(static_cast<std::size_t>(m)));
  m_leaf_of.reserve(with_spare(static_cast<std::size_t>(m)));
  std::map<std::size_t, std::size_t> memo;
  m_nodes.reserve(with_spare(m > 0 ? build_node_count(static_cast<std::size_t>(m), memo) : 0));
  m_lo.resize(static_cast<std::size_t>(m));
  m_hi.resize(static_cast<std::size_t>(m));
  m_leaf_of.assign(static_cast<std::size_t>(m), -1);
  std::vector<Item> items(static_cast<std::size_t>(m));
  for (std::int32_t i = 0; i < m; ++i) {
    set_box(mesh, i);
    items[static_cast<std::size_t>(i)] = {centroid(mesh, i), i};
  }
  build(items, 0, m, -1, 0);
}

void TetBvh::set_box(const TetMesh& mesh, std::int32_t ti) {
  Vec3 lo, hi;
  geometry::tet_box(mesh, mesh.tets[static_cast<std::size_t>(ti)], lo, hi);
  m_lo[static_cast<std::size_t>(ti)] = lo;
  m_hi[static_cast<std::size_t>(ti)] = hi;
}

std::int32_t TetBvh::build(std::vector<Item>& items, std::int32_t begin, std::int32_t end,
                           std::int32_t parent, std::int32_t depth) {
  const auto id = static_cast<std::int32_t>(m_nodes.size());
  m_nodes.emplace_back();
  m_nodes[id].parent = parent;
  m_nodes[id].depth = depth;
  m_nodes[id].size = end - begin;
  if (static_cast<std::size_t>(end - begin) <= kLeafSize) {
    for (std::int32_t i = begin; i < end; ++i) {
      const std::int32_t t = items[static_cast<std::size_t>(i)].tet;
      m_nodes[id].tets.push_back(t);
      m_leaf_of[static_cast<std::size_t>(t)] = id;
    }
    refit_leaf(id);
    return id;
  }
  Vec3 clo = items[static_cast<std::size_t>(begin)].c, chi = clo;
  for (std::int32_t i = begin; i < end; ++i) {
    clo = clo.cwiseMin(items[static_cast<std::size_t>(i)].c);
    chi = chi.cwiseMax(items[static_cast<std::size_t>(i)].c);
  }
  int axis = 0;
  (chi - clo).maxCoeff(&axis);
  const std::int32_t mid = begin + (end - begin) / 2;
  std::nth_element(items.begin() + begin, items.begin() + mid, items.begin() + end,
                   [&](const Item& a, const Item& b) {
                     return a.c[axis] < b.c[axis] || (a.c[axis] == b.c[axis] && a.tet < b.tet);
                   });
  const std::int32_t left = build(items, begin, mid, id, depth + 1);
  const std::int32_t right = build(items, mid, end, id, depth + 1);
  Node& n = m_nodes[id];
  n.left = left;
  n.right = right;
  n.lo = m_nodes[left].lo.cwiseMin(m_nodes[right].lo);
  n.hi = m_nodes[left].hi.cwiseMax(m_nodes[right].hi);
  return id;
}

void TetBvh::refit_leaf(std::int32_t node) {
  Node& n = m_nodes[node];
  n.lo = kEmptyLo;
  n.hi = kEmptyHi;
  for (std::int32_t t : n.tets) {
    n.lo = n.lo.cwiseMin(m_lo[static_cast<std::size_t>(t)]);
    n.hi = n.hi.cwiseMax(m_hi[static_cast<std::size_t>(t)]);
  }
}

void TetBvh::refit_up(std::int32_t node) {
  for (std::int32_t p = m_nodes[node].parent; p >= 0; p = m_nodes[p].parent) {
    Node& n = m_nodes[p];
    const Vec3 lo = m_nodes[n.left].lo.cwiseMin(m_nodes[n.right].lo);
    const Vec3 hi = m_nodes[n.left].hi.cwiseMax(m_nodes[n.right].hi);
    if (lo == n.lo && hi == n.hi) break;  // nothing above changes
    n.lo = lo;
    n.hi = hi;
  }
}

void TetBvh::refit(const TetMesh& mesh) {
  if (mesh.num_tets() != num_tets())
    throw std::invalid_argument("TetBvh::refit: the mesh has " + std::to_string(mesh.num_tets()) +
                                " tets, the BVH " + std::to_string(num_tets()) +
                                " (a cut was applied: call update() first)");
  for (std::int32_t i = 0; i < num_tets(); ++i) set_box(mesh, i);
  for (std::size_t k = m_nodes.size(); k-- > 0;) {  // children come after their parent
    Node& n = m_nodes[k];
    if (n.left < 0) {
      refit_leaf(static_cast<std::int32_t>(k));
    } else {
      n.lo = m_nodes[n.left].lo.cwiseMin(m_nodes[n.right].lo);
      n.hi = m_nodes[n.left].hi.cwiseMax(m_nodes[n.right].hi);
    }
  }
}

std::int32_t TetBvh::choose_leaf(std::int32_t tet) const {
  const Vec3& lo = m_lo[static_cast<std::size_t>(tet)];
  const Vec3& hi = m_hi[static_cast<std::size_t>(tet)];
  std::int32_t k = 0;
  while (m_nodes[k].left >= 0) {
    const Node& n = m_nodes[k];
    const Node& a = m_nodes[n.left];
    const Node& b = m_nodes[n.right];
    const double ga = half_area(a.lo.cwiseMin(lo), a.hi.cwiseMax(hi)) - half_area(a.lo, a.hi);
    const double gb = half_area(b.lo.cwiseMin(lo), b.hi.cwiseMax(hi)) - half_area(b.lo, b.hi);
    k = ga <= gb ? n.left : n.right;
  }
  return k;
}

void TetBvh::remove_from_leaf(std::int32_t tet) {
  const std::int32_t leaf = m_leaf_of[static_cast<std::size_t>(tet)];
  std::vector<std::int32_t>& v = m_nodes[leaf].tets;
  const auto it = std::find(v.begin(), v.end(), tet);
  if (it != v.end()) {
    *it = v.back();
    v.pop_back();
    add_size(leaf, -1);
  }
}

void TetBvh::add_size(std::int32_t node, std::int32_t delta) {
  for (std::int32_t k = node; k >= 0; k = m_nodes[k].parent) m_nodes[k].size += delta;
}

void TetBvh::collect(std::int32_t node, std::vector<std::int32_t>& tets) const {
  std::vector<std::int32_t> stack{node};
  while (!stack.empty()) {
    const Node& n = m_nodes[stack.back()];
    stack.pop_back();
    if (n.left < 0) {
      tets.insert(tets.end(), n.tets.begin(), n.tets.end());
    } else {
      stack.push_back(n.left);
      stack.push_back(n.right);
    }
  }
}

std::int32_t TetBvh::max_depth() const {
  std::int32_t lg = 0;
  while ((std::int64_t{1} << lg) < num_tets() / static_cast<std::int32_t>(kLeafSize) + 1) ++lg;
  return 2 * lg + 2;
}

// Rebuilds the subtree at `node` by median splits, in place: the new nodes are appended (so
// children still come after their parent) and the new root is copied into `node`.
void TetBvh::rebuild_subtree(const TetMesh& mesh, std::int32_t node) {
  std::vector<std::int32_t> tets;
  collect(node, tets);
  std::int64_t old_nodes = 0;  // the old subtree below `node`, cleared (refit visits them)
  if (m_nodes[node].left >= 0) {
    std::vector<std::int32_t> stack{m_nodes[node].left, m_nodes[node].right};
    while (!stack.empty()) {
      const std::int32_t k = stack.back();
      stack.pop_back();
      ++old_nodes;
      if (m_nodes[k].left >= 0) {
        stack.push_back(m_nodes[k].left);
        stack.push_back(m_nodes[k].right);
      }
      m_nodes[k] = Node{};
      m_nodes[k].lo = kEmptyLo;
      m_nodes[k].hi = kEmptyHi;
    }
  }
  std::vector<Item> items(tets.size());
  for (std::size_t k = 0; k < tets.size(); ++k) items[k] = {centroid(mesh, tets[k]), tets[k]};
  const std::int32_t parent = m_nodes[node].parent;
  const std::int32_t depth = m_nodes[node].depth;
  const std::int32_t root = build(items, 0, static_cast<std::int32_t>(items.size()), parent, depth);
  m_nodes[node] = std::move(m_nodes[root]);
  m_nodes[root] = Node{};
  m_nodes[root].lo = kEmptyLo;
  m_nodes[root].hi = kEmptyHi;
  Node& n = m_nodes[node];
  if (n.left >= 0) {
    m_nodes[n.left].parent = node;
    m_nodes[n.right].parent = node;
  } else {
    for (std::int32_t t : n.tets) m_leaf_of[static_cast<std::size_t>(t)] = node;
  }
  m_orphans += old_nodes + 1;  // and the new root's slot
  ++m_rebuilds;
}

// `leaf` is deeper than max_depth(): rebuild the highest ancestor with a child holding over
// 0.7 of its tets. With every ancestor 0.7-balanced a leaf holding a tet is at most
// log(m) / log(1 / 0.7) < 2 log2(m) deep, so one exists; the root is the fallback.
void TetBvh::rebalance(const TetMesh& mesh, std::int32_t leaf) {
  std::int32_t scapegoat = 0;
  for (std::int32_t p = m_nodes[leaf].parent; p >= 0; p = m_nodes[p].parent) {
    const Node& n = m_nodes[p];
    const std::int32_t big = std::max(m_nodes[n.left].size, m_nodes[n.right].size);
    if (static_cast<double>(big) > 0.7 * static_cast<double>(n.size)) scapegoat = p;
  }
  rebuild_subtree(mesh, scapegoat);
}

void TetBvh::split_leaf(const TetMesh& mesh, std::int32_t node) {
  std::vector<std::int32_t> tets = std::move(m_nodes[node].tets);
  m_nodes[node].tets.clear();
  std::vector<Vec3> c;
  Vec3 clo = kEmptyLo, chi = kEmptyHi;
  for (std::int32_t t : tets) {
    c.push_back(centroid(mesh, t));
    clo = clo.cwiseMin(c.back());
    chi = chi.cwiseMax(c.back());
  }
  int axis = 0;
  (chi - clo).maxCoeff(&axis);
  std::vector<std::size_t> idx(tets.size());
  std::iota(idx.begin(), idx.end(), 0);
  std::sort(idx.begin(), idx.end(), [&](std::size_t a, std::size_t b) {
    return c[a][axis] < c[b][axis] || (c[a][axis] == c[b][axis] && tets[a] < tets[b]);
  });
  const auto left = static_cast<std::int32_t>(m_nodes.size());
  m_nodes.emplace_back();
  m_nodes.emplace_back();
  const std::int32_t right = left + 1;
  for (std::size_t k = 0; k < idx.size(); ++k) {
    const std::int32_t leaf = k < idx.size() / 2 ? left : right;
    m_nodes[leaf].tets.push_back(tets[idx[k]]);
    m_leaf_of[static_cast<std::size_t>(tets[idx[k]])] = leaf;
  }
  m_nodes[left].parent = m_nodes[right].parent = node;
  m_nodes[left].depth = m_nodes[right].depth = m_nodes[node].depth + 1;
  m_nodes[left].size = static_cast<std::int32_t>(m_nodes[left].tets.size());
  m_nodes[right].size = static_cast<std::int32_t>(m_nodes[right].tets.size());
  m_nodes[node].left = left;
  m_nodes[node].right = right;
  refit_leaf(left);
  refit_leaf(right);
  m_nodes[node].lo = m_nodes[left].lo.cwiseMin(m_nodes[right].lo);
  m_nodes[node].hi = m_nodes[left].hi.cwiseMax(m_nodes[right].hi);
}

void TetBvh::update(const TetMesh& mesh, const TopologyDelta& d) {
  const auto m_before = static_cast<std::int32_t>(m_lo.size());
  const auto added = static_cast<std::int32_t>(d.added_tets.size());
  const auto removed = static_cast<std::int32_t>(d.removed_tets.size());
  if (mesh.num_tets() != m_before + added - removed ||
      d.slot_of_added.size() != d.added_tets.size())
    throw std::invalid_argument(
        "TetBvh::update: the delta does not match (BVH has " + std::to_string(m_before) +
        " tets, the mesh " + std::to_string(mesh.num_tets()) + ", the delta adds " +
        std::to_string(added) + " and removes " + std::to_string(removed) + "; was it applied?)");
  if (m_nodes.empty()) {
    *this = TetBvh(mesh, m_spare);
    return;
  }
  std::vector<std::int32_t> dirty;
  const std::int32_t reuse = std::min(added, removed);
  // Reused slots: the same leaf, a new box.
  for (std::int32_t k = 0; k < reuse; ++k) {
    const std::int32_t slot = d.removed_tets[static_cast<std::size_t>(k)];
    set_box(mesh, slot);
    dirty.push_back(m_leaf_of[static_cast<std::size_t>(slot)]);
  }
  // Appended tets: into the leaf their box enlarges least.
  for (std::int32_t k = reuse; k < added; ++k) {
    const std::int32_t id = d.slot_of_added[static_cast<std::size_t>(k)];
    m_lo.resize(static_cast<std::size_t>(id) + 1);
    m_hi.resize(static_cast<std::size_t>(id) + 1);
    m_leaf_of.resize(static_cast<std::size_t>(id) + 1, -1);
    set_box(mesh, id);
    const std::int32_t leaf = choose_leaf(id);
    m_nodes[leaf].tets.push_back(id);
    add_size(leaf, 1);
    m_leaf_of[static_cast<std::size_t>(id)] = leaf;
    // Grow the path now so the next choice sees this tet.
    m_nodes[leaf].lo = m_nodes[leaf].lo.cwiseMin(m_lo[static_cast<std::size_t>(id)]);
    m_nodes[leaf].hi = m_nodes[leaf].hi.cwiseMax(m_hi[static_cast<std::size_t>(id)]);
    refit_up(leaf);
    if (m_nodes[leaf].tets.size() > kMaxLeaf) split_leaf(mesh, leaf);
  }
  // Leftover holes, as apply() fills them: the last tet moves down, keeping its leaf.
  std::int32_t count = m_before + (added - reuse);
  for (std::int32_t k = removed; k-- > reuse;) {
    const std::int32_t hole = d.removed_tets[static_cast<std::size_t>(k)];
    const std::int32_t last = count - 1;
    dirty.push_back(m_leaf_of[static_cast<std::size_t>(hole)]);
    remove_from_leaf(hole);
    if (hole != last) {
      const std::int32_t leaf = m_leaf_of[static_cast<std::size_t>(last)];
      std::vector<std::int32_t>& v = m_nodes[leaf].tets;
      std::replace(v.begin(), v.end(), last, hole);
      m_leaf_of[static_cast<std::size_t>(hole)] = leaf;
      m_lo[static_cast<std::size_t>(hole)] = m_lo[static_cast<std::size_t>(last)];
      m_hi[static_cast<std::size_t>(hole)] = m_hi[static_cast<std::size_t>(last)];
    }
    --count;
  }
  m_lo.resize(static_cast<std::size_t>(count));
  m_hi.resize(static_cast<std::size_t>(count));
  m_leaf_of.resize(static_cast<std::size_t>(count));
  std::sort(dirty.begin(), dirty.end());
  dirty.erase(std::unique(dirty.begin(), dirty.end()), dirty.end());
  for (std::int32_t node : dirty) {
    if (m_nodes[node].left < 0) {
      refit_leaf(node);
    } else {  // a leaf split meanwhile
      Node& n = m_nodes[node];
      n.lo = m_nodes[n.left].lo.cwiseMin(m_nodes[n.right].lo);
      n.hi = m_nodes[n.left].hi.cwiseMax(m_nodes[n.right].hi);
    }
    // Walk up without the early exit: a box may shrink as well as grow.
    for (std::int32_t p = m_nodes[node].parent; p >= 0; p = m_nodes[p].parent) {
      Node& n = m_nodes[p];
      n.lo = m_nodes[n.left].lo.cwiseMin(m_nodes[n.right].lo);
      n.hi = m_nodes[n.left].hi.cwiseMax(m_nodes[n.right].hi);
    }
  }
  // Depth bound: appended tets are the only ones that deepen the tree (no hole moves then).
  const std::int32_t limit = max_depth();
  for (std::int32_t k = reuse; k < added; ++k) {
    const std::int32_t id = d.slot_of_added[static_cast<std::size_t>(k)];
    if (id >= num_tets()) continue;
    const std::int32_t leaf = m_leaf_of[static_cast<std::size_t>(id)];
    if (m_nodes[leaf].depth > limit) rebalance(mesh, leaf);
  }
  // Reclaim the nodes rebuilds left behind once they outnumber the live ones.
  if (m_orphans > static_cast<std::int64_t>(m_nodes.size()) / 2) {
    const std::int64_t rebuilds = m_rebuilds;
    *this = TetBvh(mesh, m_spare);
    m_rebuilds = rebuilds + 1;
  }
}

std::int32_t TetBvh::depth() const {
  std::int32_t best = 0;
  if (m_nodes.empty()) return 0;
  std::vector<std::pair<std::int32_t, std::int32_t>> stack{{0, 0}};  // reachable nodes only
  while (!stack.empty()) {
    const auto [k, d] = stack.back();
    stack.pop_back();
    const Node& n = m_nodes[k];
    if (n.left < 0) {
      best = std::max(best, d);
    } else {
      stack.push_back({n.left, d + 1});
      stack.push_back({n.right, d + 1});
    }
  }
  return best;
}

void TetBvh::query(const Vec3& lo, const Vec3& hi, std::vector<std::int32_t>& out) const {
  if (m_nodes.empty()) return;
  std::int32_t stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = m_nodes[stack[--top]];
    if (!((n.lo.array() <= hi.array()).all() && (n.hi.array() >= lo.array()).all())) continue;
    if (n.left < 0) {
      for (std::int32_t t : n.tets)
        if ((m_lo[static_cast<std::size_t>(t)].array() <= hi.array()).all() &&
            (m_hi[static_cast<std::size_t>(t)].array() >= lo.array()).all())
          out.push_back(t);
    } else if (top + 2 <= 128) {
      stack[top++] = n.left;
      stack[top++] = n.right;
    } else {  // deeper than any balanced tree: fall back to a heap stack
      std::vector<std::int32_t> more{n.left, n.right};
      while (!more.empty()) {
        const Node& q = m_nodes[more.back()];
        more.pop_back();
        if (!((q.lo.array() <= hi.array()).all() && (q.hi.array() >= lo.array()).all())) continue;
        if (q.left < 0) {
          for (std::int32_t t : q.tets)
            if ((m_lo[static_cast<std::size_t>(t)].array() <= hi.array()).all() &&
                (m_hi[static_cast<std::size_t>(t)].array() >= lo.array()).all())
              out.push_back(t);
        } else {
          more.push_back(q.left);
          more.push_back(q.right);
        }
      }
    }
  }
}

TetBoxQuery TetBvh::as_query() const {
  return [this](const Vec3& lo, const Vec3& hi, std::vector<std::int32_t>& out) {
    query(lo, hi, out);
  };
}

}  // namespace serosa::cutting

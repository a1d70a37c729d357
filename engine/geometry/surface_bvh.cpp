#include "engine/geometry/surface_bvh.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>

#include "engine/geometry/point_triangle.h"
#include "engine/geometry/ray_triangle.h"

namespace serosa::geometry {
namespace {

constexpr std::size_t kBuildLeaf = 4;  // faces per leaf after build()
constexpr std::size_t kMaxLeaf = 8;    // a leaf growing past this is split by update()

const Vec3& at(std::span<const Vec3> x, std::int32_t v) { return x[static_cast<std::size_t>(v)]; }

Vec3 centroid(std::span<const Vec3> x, const Tri& t) {
  return (at(x, t[0]) + at(x, t[1]) + at(x, t[2])) / 3.0;
}

double half_area(const Vec3& lo, const Vec3& hi) {
  const Vec3 e = (hi - lo).cwiseMax(0.0);
  return e.x() * e.y() + e.y() * e.z() + e.z() * e.x();
}

// Squared distance from p to the box [lo, hi] (infinite for an empty box).
double box_dist2(const Vec3& p, const Vec3& lo, const Vec3& hi) {
  if (lo.x() > hi.x()) return std::numeric_limits<double>::infinity();
  return (lo - p).cwiseMax(p - hi).cwiseMax(0.0).squaredNorm();
}

// True when o + t d meets the box for some t in [t0, t1] (slab test; zero components of d
// handled without dividing).
bool ray_box(const Vec3& o, const Vec3& d, const Vec3& lo, const Vec3& hi, double t0, double t1) {
  for (int k = 0; k < 3; ++k) {
    if (d[k] == 0.0) {
      if (o[k] < lo[k] || o[k] > hi[k]) return false;
      continue;
    }
    double a = (lo[k] - o[k]) / d[k];
    double b = (hi[k] - o[k]) / d[k];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
    if (!(t0 <= t1)) return false;  // also NaN
  }
  return true;
}

// Pads a box so that culling stays conservative under rounding.
void pad(Vec3& lo, Vec3& hi) {
  if (lo.x() > hi.x()) return;
  const double size =
      std::max((hi - lo).maxCoeff(), std::max(lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff()));
  const Vec3 e = Vec3::Constant(1e-9 * size + 1e-300);
  lo -= e;
  hi += e;
}

}  // namespace

void SurfaceBvh::fit_leaf(Node& n, std::span<const Vec3> x) const {
  n.lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  n.hi = -n.lo;
  for (std::int32_t slot : leaves_[static_cast<std::size_t>(n.leaf)])
    for (std::int32_t v : tris_[static_cast<std::size_t>(slot)]) {
      n.lo = n.lo.cwiseMin(at(x, v));
      n.hi = n.hi.cwiseMax(at(x, v));
    }
  pad(n.lo, n.hi);
}

std::int32_t SurfaceBvh::make_leaf(std::span<const std::int32_t> slots) {
  Node n;
  n.leaf = static_cast<std::int32_t>(leaves_.size());
  leaves_.emplace_back(slots.begin(), slots.end());
  const auto id = static_cast<std::int32_t>(nodes_.size());
  nodes_.push_back(n);
  const auto& list = leaves_.back();
  for (std::size_t i = 0; i < list.size(); ++i) {
    slot_node_[static_cast<std::size_t>(list[i])] = id;
    slot_pos_[static_cast<std::size_t>(list[i])] = static_cast<std::int32_t>(i);
  }
  return id;
}

std::int32_t SurfaceBvh::build_range(std::vector<std::int32_t>& slots, std::size_t begin,
                                     std::size_t end, std::span<const Vec3> x) {
  if (end - begin <= kBuildLeaf)
    return make_leaf(std::span<const std::int32_t>(slots).subspan(begin, end - begin));
  // Split at the centroid median along the longest axis of the centroids' box.
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 hi = -lo;
  for (std::size_t i = begin; i < end; ++i) {
    const Vec3 c = centroid(x, tris_[static_cast<std::size_t>(slots[i])]);
    lo = lo.cwiseMin(c);
    hi = hi.cwiseMax(c);
  }
  int axis = 0;
  (hi - lo).maxCoeff(&axis);
  const std::size_t mid = begin + (end - begin) / 2;
  const auto first = slots.begin() + static_cast<std::ptrdiff_t>(begin);
  std::nth_element(first, slots.begin() + static_cast<std::ptrdiff_t>(mid),
                   slots.begin() + static_cast<std::ptrdiff_t>(end),
                   [&](std::int32_t p, std::int32_t q) {
                     const double cp = centroid(x, tris_[static_cast<std::size_t>(p)])[axis];
                     const double cq = centroid(x, tris_[static_cast<std::size_t>(q)])[axis];
                     return cp < cq || (cp == cq && p < q);
                   });
  const auto id = static_cast<std::int32_t>(nodes_.size());
  nodes_.emplace_back();
  const std::int32_t left = build_range(slots, begin, mid, x);
  const std::int32_t right = build_range(slots, mid, end, x);
  nodes_[static_cast<std::size_t>(id)].child[0] = left;
  nodes_[static_cast<std::size_t>(id)].child[1] = right;
  return id;
}

void SurfaceBvh::build(const SurfaceMesh& s, std::span<const Vec3> x) {
  for (std::size_t i = 0; i < s.faces.size(); ++i)
    for (std::int32_t v : s.faces[i])
      if (v < 0 || static_cast<std::size_t>(v) >= x.size())
        throw std::invalid_argument("SurfaceBvh: face " + std::to_string(i) + " names node " +
                                    std::to_string(v) + ", outside the positions");
  tris_ = s.faces;
  nodes_.clear();
  leaves_.clear();
  slot_node_.assign(tris_.size(), -1);
  slot_pos_.assign(tris_.size(), -1);
  std::vector<std::int32_t> slots(tris_.size());
  for (std::size_t i = 0; i < slots.size(); ++i) slots[i] = static_cast<std::int32_t>(i);
  nodes_.reserve(2 * (tris_.size() / kBuildLeaf + 1));
  build_range(slots, 0, slots.size(), x);
  refit(x);
}

void SurfaceBvh::refit(std::span<const Vec3> x) {
  for (std::size_t i = nodes_.size(); i-- > 0;) {
    Node& n = nodes_[i];
    if (n.leaf >= 0) {
      fit_leaf(n, x);
    } else {
      const Node& a = nodes_[static_cast<std::size_t>(n.child[0])];
      const Node& b = nodes_[static_cast<std::size_t>(n.child[1])];
      n.lo = a.lo.cwiseMin(b.lo);
      n.hi = a.hi.cwiseMax(b.hi);
    }
  }
}

void SurfaceBvh::remove_slot(std::int32_t slot) {
  const auto s = static_cast<std::size_t>(slot);
  auto& list =
      leaves_[static_cast<std::size_t>(nodes_[static_cast<std::size_t>(slot_node_[s])].leaf)];
  const auto pos = static_cast<std::size_t>(slot_pos_[s]);
  list[pos] = list.back();
  slot_pos_[static_cast<std::size_t>(list[pos])] = static_cast<std::int32_t>(pos);
  list.pop_back();
  slot_node_[s] = -1;
  slot_pos_[s] = -1;
}

void SurfaceBvh::split_leaf(std::int32_t node, std::span<const Vec3> x) {
  std::vector<std::int32_t> slots =
      std::move(leaves_[static_cast<std::size_t>(nodes_[static_cast<std::size_t>(node)].leaf)]);
  const std::int32_t reuse = nodes_[static_cast<std::size_t>(node)].leaf;
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 hi = -lo;
  for (std::int32_t s : slots) {
    const Vec3 c = centroid(x, tris_[static_cast<std::size_t>(s)]);
    lo = lo.cwiseMin(c);
    hi = hi.cwiseMax(c);
  }
  int axis = 0;
  (hi - lo).maxCoeff(&axis);
  std::sort(slots.begin(), slots.end(), [&](std::int32_t p, std::int32_t q) {
    const double cp = centroid(x, tris_[static_cast<std::size_t>(p)])[axis];
    const double cq = centroid(x, tris_[static_cast<std::size_t>(q)])[axis];
    return cp < cq || (cp == cq && p < q);
  });
  const std::size_t mid = slots.size() / 2;
  const std::span<const std::int32_t> all(slots);
  const std::int32_t left = make_leaf(all.first(mid));
  const std::int32_t right = make_leaf(all.subspan(mid));
  // The right leaf's list (last) moves into the emptied old list's index, so leaves_ grows by
  // one per split; the left leaf's list keeps its index.
  leaves_[static_cast<std::size_t>(reuse)] = std::move(leaves_.back());
  leaves_.pop_back();
  nodes_[static_cast<std::size_t>(right)].leaf = reuse;
  for (std::int32_t i : {left, right}) fit_leaf(nodes_[static_cast<std::size_t>(i)], x);
  Node& n = nodes_[static_cast<std::size_t>(node)];
  n.leaf = -1;
  n.child[0] = left;
  n.child[1] = right;
}

void SurfaceBvh::insert_slot(std::int32_t slot, std::span<const Vec3> x) {
  const Tri& t = tris_[static_cast<std::size_t>(slot)];
  Vec3 lo = at(x, t[0]).cwiseMin(at(x, t[1])).cwiseMin(at(x, t[2]));
  Vec3 hi = at(x, t[0]).cwiseMax(at(x, t[1])).cwiseMax(at(x, t[2]));
  pad(lo, hi);
  if (nodes_.empty()) {
    leaves_.clear();
    make_leaf({});
  }
  // Descend to the child whose box grows least, growing the boxes on the way.
  std::int32_t i = 0;
  for (;;) {
    Node& n = nodes_[static_cast<std::size_t>(i)];
    n.lo = n.lo.cwiseMin(lo);
    n.hi = n.hi.cwiseMax(hi);
    if (n.leaf >= 0) break;
    double best = std::numeric_limits<double>::infinity();
    std::int32_t pick = n.child[0];
    for (std::int32_t c : n.child) {
      const Node& k = nodes_[static_cast<std::size_t>(c)];
      const double before = k.lo.x() > k.hi.x() ? 0.0 : half_area(k.lo, k.hi);
      const double grow = half_area(k.lo.cwiseMin(lo), k.hi.cwiseMax(hi)) - before;
      if (grow < best) {
        best = grow;
        pick = c;
      }
    }
    i = pick;
  }
  auto& list = leaves_[static_cast<std::size_t>(nodes_[static_cast<std::size_t>(i)].leaf)];
  slot_node_[static_cast<std::size_t>(slot)] = i;
  slot_pos_[static_cast<std::size_t>(slot)] = static_cast<std::int32_t>(list.size());
  list.push_back(slot);
  if (list.size() > kMaxLeaf) split_leaf(i, x);
}

void SurfaceBvh::update(const SurfaceMesh& s, std::span<const std::int32_t> changed_slots,
                        std::span<const Vec3> x) {
  for (std::size_t i = 0; i < s.faces.size(); ++i)
    for (std::int32_t v : s.faces[i])
      if (v < 0 || static_cast<std::size_t>(v) >= x.size())
        throw std::invalid_argument("SurfaceBvh: face " + std::to_string(i) + " names node " +
                                    std::to_string(v) + ", outside the positions");
  const auto old_n = static_cast<std::int32_t>(tris_.size());
  const auto new_n = static_cast<std::int32_t>(s.faces.size());
  // 1. Slots that are gone or changed leave their leaves.
  for (std::int32_t slot = new_n; slot < old_n; ++slot) remove_slot(slot);
  std::vector<std::int32_t> redo;
  redo.reserve(changed_slots.size() + static_cast<std::size_t>(std::max(0, new_n - old_n)));
  for (std::int32_t slot : changed_slots) {
    if (slot < 0 || slot >= new_n)
      throw std::invalid_argument("SurfaceBvh::update: changed slot " + std::to_string(slot) +
                                  " outside the surface's " + std::to_string(new_n) + " faces");
    if (slot < old_n && slot_node_[static_cast<std::size_t>(slot)] >= 0) {
      remove_slot(slot);
      redo.push_back(slot);
    }
  }
  for (std::int32_t slot = old_n; slot < new_n; ++slot) redo.push_back(slot);
  // 2. New node ids, then re-insertion.
  tris_.resize(static_cast<std::size_t>(new_n));
  slot_node_.resize(static_cast<std::size_t>(new_n), -1);
  slot_pos_.resize(static_cast<std::size_t>(new_n), -1);
  for (std::int32_t slot : redo) {
    tris_[static_cast<std::size_t>(slot)] = s.faces[static_cast<std::size_t>(slot)];
    insert_slot(slot, x);
  }
  refit(x);
}

std::int32_t SurfaceBvh::depth() const {
  if (nodes_.empty()) return 0;
  std::int32_t deepest = 0;
  std::vector<std::pair<std::int32_t, std::int32_t>> stack{{0, 0}};
  while (!stack.empty()) {
    const auto [i, d] = stack.back();
    stack.pop_back();
    deepest = std::max(deepest, d);
    const Node& n = nodes_[static_cast<std::size_t>(i)];
    if (n.leaf < 0)
      for (std::int32_t c : n.child) stack.emplace_back(c, d + 1);
  }
  return deepest;
}

std::optional<ClosestHit> SurfaceBvh::closest_point(std::span<const Vec3> x, const Vec3& p,
                                                    double max_distance) const {
  std::optional<ClosestHit> best;
  if (nodes_.empty()) return best;
  double best_d2 = max_distance * max_distance;
  std::vector<std::int32_t> stack;
  stack.reserve(64);
  stack.push_back(0);
  while (!stack.empty()) {
    const Node& n = nodes_[static_cast<std::size_t>(stack.back())];
    stack.pop_back();
    if (box_dist2(p, n.lo, n.hi) > best_d2) continue;
    if (n.leaf >= 0) {
      for (std::int32_t slot : leaves_[static_cast<std::size_t>(n.leaf)]) {
        const Tri& t = tris_[static_cast<std::size_t>(slot)];
        const geometry::TrianglePoint q =
            geometry::closest_point_on_triangle(p, at(x, t[0]), at(x, t[1]), at(x, t[2]));
        if (q.dist2 < best_d2 || (q.dist2 == best_d2 && (!best || slot < best->face))) {
          best_d2 = q.dist2;
          best = ClosestHit{slot, q.point, q.bary, std::sqrt(q.dist2)};
        }
      }
      continue;
    }
    // Nearer child on top of the stack.
    const Node& a = nodes_[static_cast<std::size_t>(n.child[0])];
    const Node& b = nodes_[static_cast<std::size_t>(n.child[1])];
    const bool a_first = box_dist2(p, a.lo, a.hi) <= box_dist2(p, b.lo, b.hi);
    stack.push_back(a_first ? n.child[1] : n.child[0]);
    stack.push_back(a_first ? n.child[0] : n.child[1]);
  }
  return best;
}

template <class Visit>
void SurfaceBvh::ray_traverse(std::span<const Vec3> x, const Vec3& o, const Vec3& d, double t_max,
                              Visit&& visit) const {
  if (nodes_.empty()) return;
  std::vector<std::int32_t> stack;
  stack.reserve(64);
  stack.push_back(0);
  double limit = t_max;
  while (!stack.empty()) {
    const Node& n = nodes_[static_cast<std::size_t>(stack.back())];
    stack.pop_back();
    if (!ray_box(o, d, n.lo, n.hi, 0.0, limit)) continue;
    if (n.leaf >= 0) {
      for (std::int32_t slot : leaves_[static_cast<std::size_t>(n.leaf)]) {
        const Tri& t = tris_[static_cast<std::size_t>(slot)];
        RayTriangleHit h;
        if (ray_triangle(o, d, at(x, t[0]), at(x, t[1]), at(x, t[2]), 0.0, limit, h))
          limit = visit(slot, h);
      }
      continue;
    }
    stack.push_back(n.child[1]);
    stack.push_back(n.child[0]);
  }
}

std::optional<RayHit> SurfaceBvh::raycast(std::span<const Vec3> x, const Vec3& origin,
                                          const Vec3& dir, double t_max) const {
  std::optional<RayHit> best;
  ray_traverse(x, origin, dir, t_max, [&](std::int32_t slot, const RayTriangleHit& h) {
    if (!best || h.t < best->t || (h.t == best->t && slot < best->face))
      best = RayHit{slot, h.t, h.bary};
    return best->t;  // later hits must be at least as near
  });
  return best;
}

std::optional<RayHit> SurfaceBvh::segment_first(std::span<const Vec3> x, const Vec3& a,
                                                const Vec3& b) const {
  return raycast(x, a, b - a, 1.0);
}

void SurfaceBvh::segment_all(std::span<const Vec3> x, const Vec3& a, const Vec3& b,
                             std::vector<RayHit>& hits) const {
  hits.clear();
  ray_traverse(x, a, b - a, 1.0, [&](std::int32_t slot, const RayTriangleHit& h) {
    hits.push_back(RayHit{slot, h.t, h.bary});
    return 1.0;
  });
  std::sort(hits.begin(), hits.end(), [](const RayHit& p, const RayHit& q) {
    return std::tie(p.t, p.face) < std::tie(q.t, q.face);
  });
}

}  // namespace serosa::geometry

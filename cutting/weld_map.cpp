#include "cutting/weld_map.h"

#include <algorithm>

namespace serosa::cutting {

std::int32_t WeldMap::push(const NodeParent& p) {
  m_new.push_back(p);
  return m_next++;
}

EdgePair WeldMap::edge_point(std::int32_t a, std::int32_t b, double t_from_lo, bool open) {
  const std::uint64_t key = edge_key(a, b);
  if (auto it = m_edges.find(key); it != m_edges.end()) return it->second;
  NodeParent p;
  p.count = 2;
  p.nodes = {std::min(a, b), std::max(a, b), -1, -1};
  p.weights = {1.0 - t_from_lo, t_from_lo, 0.0, 0.0};
  EdgePair pair;
  pair.pos = push(p);
  pair.neg = open ? push(p) : pair.pos;
  m_pairs += open ? 1 : 0;
  m_edges.emplace(key, pair);
  return pair;
}

std::int32_t WeldMap::clone(std::int32_t a) {
  if (auto it = m_clones.find(a); it != m_clones.end()) return it->second;
  NodeParent p;
  p.count = 1;
  p.nodes = {a, -1, -1, -1};
  p.weights = {1.0, 0.0, 0.0, 0.0};
  const std::int32_t id = push(p);
  m_clones.emplace(a, id);
  return id;
}

std::optional<std::int32_t> WeldMap::find_clone(std::int32_t a) const {
  if (auto it = m_clones.find(a); it != m_clones.end()) return it->second;
  return std::nullopt;
}

std::int32_t WeldMap::add_point(const NodeParent& parent) { return push(parent); }

}  // namespace serosa::cutting

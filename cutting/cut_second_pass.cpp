// The second pass (docs/cutting.md, point 7): a local mesh of the first pass's result near the
// blade, cut again, and the composition of both deltas into one against the input mesh (new
// nodes' parents flattened to its nodes; every point of a pinned tet is a combination of its
// four).
#include "cutting/cut_second_pass.h"

#include <unordered_map>

#include "cutting/cut_state.h"

namespace serosa::cutting::detail {
namespace {

// The part of the mesh after the first pass that the second pass cuts.
struct LocalMesh {
  TetMesh mesh;
  std::vector<std::int32_t> global_of;  ///< local node -> global id (new nodes: n_old + k)
  /// Local tet -> old tet id, or -1 - k for added tet k of the first delta.
  std::vector<std::int32_t> origin;
};

// The candidates of the first pass it kept (cands: old tet ids, ascending), then its pieces.
LocalMesh build_local_mesh(const TetMesh& mesh, const TopologyDelta& d1,
                           const std::vector<std::int32_t>& cands) {
  const std::int32_t n_old = mesh.num_nodes();
  LocalMesh local;
  std::unordered_map<std::int32_t, std::int32_t> lid;  // global id -> local node
  auto local_node = [&](std::int32_t g) {
    auto [it, fresh] = lid.try_emplace(g, static_cast<std::int32_t>(local.global_of.size()));
    if (fresh) {
      local.global_of.push_back(g);
      Vec3 r = Vec3::Zero(), x = Vec3::Zero();
      if (g < n_old) {
        r = mesh.rest[static_cast<std::size_t>(g)];
        x = mesh.x[static_cast<std::size_t>(g)];
      } else {
        const NodeParent& p = d1.added_nodes[static_cast<std::size_t>(g - n_old)];
        for (int k = 0; k < p.count; ++k) {
          r += p.weights[k] * mesh.rest[static_cast<std::size_t>(p.nodes[k])];
          x += p.weights[k] * mesh.x[static_cast<std::size_t>(p.nodes[k])];
        }
      }
      local.mesh.rest.push_back(r);
      local.mesh.x.push_back(x);
    }
    return it->second;
  };
  auto add_local = [&](const Tet& t, std::uint16_t g, std::int32_t o) {
    local.mesh.tets.push_back(
        {local_node(t[0]), local_node(t[1]), local_node(t[2]), local_node(t[3])});
    local.mesh.group.push_back(g);
    local.origin.push_back(o);
  };
  for (std::int32_t ti : cands)
    if (!std::binary_search(d1.removed_tets.begin(), d1.removed_tets.end(), ti))
      add_local(mesh.tets[static_cast<std::size_t>(ti)], mesh.group[static_cast<std::size_t>(ti)],
                ti);
  for (std::size_t k = 0; k < d1.added_tets.size(); ++k)
    add_local(d1.added_tets[k], d1.added_groups[k], -1 - static_cast<std::int32_t>(k));
  local.mesh.fill_node_state();
  return local;
}

// Parents p of a second-pass node (local node ids) flattened to nodes of the input mesh (n_old
// nodes; first-pass nodes replaced by their parents), rounding-zero weights dropped and the rest
// renormalised. False when more than four remain (a NodeParent holds four) or none.
bool flatten_parent(const NodeParent& p, const LocalMesh& local, const TopologyDelta& d1,
                    std::int32_t n_old, NodeParent& out) {
  std::array<std::int32_t, 8> ids{};
  std::array<double, 8> w{};
  int count = 0;
  auto add = [&](std::int32_t id, double weight) {
    for (int k = 0; k < count; ++k)
      if (ids[static_cast<std::size_t>(k)] == id) {
        w[static_cast<std::size_t>(k)] += weight;
        return true;
      }
    if (count == 8) return false;
    ids[static_cast<std::size_t>(count)] = id;
    w[static_cast<std::size_t>(count++)] = weight;
    return true;
  };
  bool ok = true;
  for (int k = 0; k < p.count && ok; ++k) {
    const std::int32_t g = local.global_of[static_cast<std::size_t>(p.nodes[k])];
    if (g < n_old) {
      ok = add(g, p.weights[k]);
      continue;
    }
    const NodeParent& q = d1.added_nodes[static_cast<std::size_t>(g - n_old)];
    for (int l = 0; l < q.count && ok; ++l) ok = add(q.nodes[l], p.weights[k] * q.weights[l]);
  }
  NodeParent f;
  double sum = 0.0;
  for (int k = 0; k < count && ok; ++k) {
    if (std::abs(w[static_cast<std::size_t>(k)]) <= 1e-15) continue;
    if (f.count == 4) ok = false;
    if (!ok) break;
    f.nodes[f.count] = ids[static_cast<std::size_t>(k)];
    f.weights[f.count] = w[static_cast<std::size_t>(k)];
    sum += f.weights[f.count];
    ++f.count;
  }
  if (!ok || f.count == 0) return false;
  for (int k = 0; k < f.count; ++k) f.weights[k] /= sum;
  out = f;
  return true;
}

// The first delta d1 (against the input mesh, n_old nodes) followed by the second d2 (against
// the local mesh), as one delta against the input mesh. originals: the input mesh's tets d2
// removed. False when a new node cannot be flattened or is used by no tet.
bool compose(std::int32_t n_old, const LocalMesh& local, const TopologyDelta& d1,
             const TopologyDelta& d2, TopologyDelta& out, std::int64_t& originals) {
  const auto n1 = static_cast<std::int32_t>(d1.added_nodes.size());
  const std::int32_t n_local = local.mesh.num_nodes();
  out.removed_tets = d1.removed_tets;
  std::vector<char> dropped(d1.added_tets.size(), 0);
  for (std::int32_t lt : d2.removed_tets) {
    const std::int32_t o = local.origin[static_cast<std::size_t>(lt)];
    if (o >= 0) {
      out.removed_tets.push_back(o);
      ++originals;
    } else {
      dropped[static_cast<std::size_t>(-1 - o)] = 1;
    }
  }
  std::sort(out.removed_tets.begin(), out.removed_tets.end());
  auto global_node = [&](std::int32_t l) {
    return l < n_local ? local.global_of[static_cast<std::size_t>(l)] : n_old + n1 + (l - n_local);
  };
  for (std::size_t k = 0; k < d1.added_tets.size(); ++k)
    if (!dropped[k]) {
      out.added_tets.push_back(d1.added_tets[k]);
      out.added_groups.push_back(d1.added_groups[k]);
    }
  for (std::size_t k = 0; k < d2.added_tets.size(); ++k) {
    const Tet& t = d2.added_tets[k];
    out.added_tets.push_back(
        {global_node(t[0]), global_node(t[1]), global_node(t[2]), global_node(t[3])});
    out.added_groups.push_back(d2.added_groups[k]);
  }
  out.added_nodes = d1.added_nodes;
  for (const NodeParent& p : d2.added_nodes) {
    NodeParent f;
    if (!flatten_parent(p, local, d1, n_old, f)) return false;
    out.added_nodes.push_back(f);
  }
  // Every new node is used.
  std::vector<char> used(out.added_nodes.size(), 0);
  for (const Tet& t : out.added_tets)
    for (std::int32_t v : t)
      if (v >= n_old) used[static_cast<std::size_t>(v - n_old)] = 1;
  return std::find(used.begin(), used.end(), 0) == used.end();
}

// The first pass's counts with the second's added (pinned counts are the second's: what is
// still pinned after it), and the composed delta's sizes.
CutStats merged_stats(const CutStats& first, const CutStats& s2, std::int64_t originals,
                      const TopologyDelta& out) {
  CutStats st = first;
  st.second_pass_tets = s2.tets_removed;
  st.second_pass_originals = originals;
  st.tets_pinned = s2.tets_pinned;
  st.pinned_centred = s2.pinned_centred;
  st.tets_short += s2.tets_short;
  st.tets_grazed += s2.tets_grazed;
  st.degenerate_tets += s2.degenerate_tets;
  st.edge_pairs += s2.edge_pairs;
  st.edge_singles += s2.edge_singles;
  st.clones += s2.clones;
  st.clones_on_outline += s2.clones_on_outline;
  st.steiner_points += s2.steiner_points;
  st.face_points += s2.face_points;
  st.tets_removed = static_cast<std::int64_t>(out.removed_tets.size());
  st.tets_added = static_cast<std::int64_t>(out.added_tets.size());
  st.nodes_added = static_cast<std::int64_t>(out.added_nodes.size());
  return st;
}

}  // namespace

bool second_pass(const TetMesh& mesh, const ConvexPolygon& blade, const CutOptions& options,
                 const TetBoxQuery& query, CutResult& first) {
  const double tol = first.stats.tolerance_m;
  std::vector<std::int32_t> cands;
  const Vec3 grow = Vec3::Constant(2.0 * tol);
  query(blade.box_min() - grow, blade.box_max() + grow, cands);
  std::sort(cands.begin(), cands.end());
  cands.erase(std::unique(cands.begin(), cands.end()), cands.end());
  const LocalMesh local = build_local_mesh(mesh, first.delta, cands);
  CutOptions once = options;  // no third pass: what the second pass cannot open, it fans
  once.reopen_pinned = false;
  const CutResult second = cut_pass(local.mesh, blade, once, brute_force_query(local.mesh), tol);
  if (second.delta.empty()) return true;
  TopologyDelta out;
  std::int64_t originals = 0;
  if (!compose(mesh.num_nodes(), local, first.delta, second.delta, out, originals)) return false;
  first.stats = merged_stats(first.stats, second.stats, originals, out);
  first.delta = std::move(out);
  return true;
}

}  // namespace serosa::cutting::detail

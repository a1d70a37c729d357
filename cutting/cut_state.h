// What one pattern cut (cut_mesh) records while it builds its delta, shared by its steps: the
// classification of nodes, edges and tets, the points it creates on faces and coplanar edges,
// and the lookups several steps use. Internal to cut_mesh; the steps are, in order:
// cut_classify (signs, cases, cut points), cut_partial (partial tets: the blade's share S of the
// section and the crack's apex), cut_coplanar (coplanar faces the blade covers partly),
// cut_welding (which edges open, which coplanar nodes are cloned), cut_emit and
// cut_emit_partial (the pieces) and cut_second_pass. docs/cutting.md explains the algorithm.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "cutting/case_table.h"
#include "cutting/convex_polygon.h"
#include "cutting/cut_types.h"
#include "cutting/section_triangulation.h"
#include "cutting/weld_map.h"
#include "engine/tet_faces.h"
#include "engine/tet_mesh.h"

namespace serosa::cutting::detail {

using V2 = Eigen::Vector2d;
using FaceKey = std::array<std::int32_t, 3>;  ///< a face's node ids, sorted ascending

/// A point as a combination of original nodes (the weights apply() gives the new node).
struct Combo {
  std::array<std::int32_t, 4> nodes{-1, -1, -1, -1};  ///< the first `count` used
  std::array<double, 4> w{0.0, 0.0, 0.0, 0.0};        ///< weights, summing to 1 when complete
  int count = 0;

  /// The original node n itself.
  static Combo of(std::int32_t n) {
    Combo c;
    c.add(n, 1.0);
    return c;
  }
  /// Adds weight to node n (merged with n's weight when n is already a parent).
  void add(std::int32_t n, double weight) {
    for (int k = 0; k < count; ++k)
      if (nodes[k] == n) {
        w[k] += weight;
        return;
      }
    nodes[count] = n;
    w[count] = weight;
    ++count;
  }
  /// Adds scale times every parent of o.
  void add(const Combo& o, double scale) {
    for (int k = 0; k < o.count; ++k) add(o.nodes[k], o.w[k] * scale);
  }
  /// Rest position, m.
  [[nodiscard]] Vec3 rest(const TetMesh& m) const {
    Vec3 r = Vec3::Zero();
    for (int k = 0; k < count; ++k) r += w[k] * m.rest[nodes[k]];
    return r;
  }
  /// Current position, m.
  [[nodiscard]] Vec3 cur(const TetMesh& m) const {
    Vec3 r = Vec3::Zero();
    for (int k = 0; k < count; ++k) r += w[k] * m.x[nodes[k]];
    return r;
  }
  [[nodiscard]] NodeParent parent() const {
    NodeParent p;
    p.count = static_cast<std::uint8_t>(count);
    for (int k = 0; k < count; ++k) {
      p.nodes[k] = nodes[k];
      p.weights[k] = w[k];
    }
    return p;
  }
};

/// The cut point on edge (a, b) at parameter t from the smaller id to the larger.
inline Combo edge_combo(std::int32_t a, std::int32_t b, double t) {
  Combo c;
  c.add(std::min(a, b), 1.0 - t);
  c.add(std::max(a, b), t);
  return c;
}

struct NodeInfo {
  double phi = 0.0;  ///< signed distance to the plane, m
  Sign sign = Sign::kZero;
  double margin = 0.0;  ///< coplanar node: inside margin in the polygon, m
  bool inside = false;  ///< coplanar node inside the polygon grown by tol
  bool strict = false;  ///< coplanar node inside the polygon by more than tol
};

struct EdgeInfo {
  double t = 0.0;       ///< cut point parameter from min id to max id
  bool inside = false;  ///< cut point inside the polygon (grown by tol): the edge is split
  bool strict = false;  ///< cut point inside by more than tol: may open
  bool open = false;    ///< strict and no pinned tet around it: two nodes
  std::vector<std::int32_t> tets;  ///< candidate indices of the tets around it
};

/// A corner of S that may open: a coplanar node (node >= 0) or a cut point (edge != 0); face
/// points and blade corners (neither) are welded.
struct OpenKey {
  std::int32_t node = -1;
  std::uint64_t edge = 0;
};
/// A side of S on the section's boundary (a "run"), in plane coordinates (m).
struct RunSide {
  V2 a = V2::Zero(), b = V2::Zero();
  OpenKey ka, kb;
};

struct TetInfo {
  std::array<Sign, 4> sign{};
  int code = 0;            ///< case_code(sign)
  bool straddles = false;  ///< has a + and a - node
  bool complete = false;   ///< straddles and its whole section lies in the polygon
  bool pinned = false;     ///< partial, but the crack cannot stop inside it: split welded
  bool interacts = false;  ///< partial: the blade meets its section (else left whole)
  Combo apex;              ///< partial, not pinned: the cone apex on the crack's front
  Combo centre;            ///< pinned with has_centre: a point strictly inside S, on the plane
  bool has_centre = false;
  /// Partial, not pinned: S's sides on the section's boundary (the crack is the fan from the
  /// apex over those with an end that opens), the apex and S's area, in plane coordinates.
  std::vector<RunSide> runs;
  V2 apex2 = V2::Zero();
  double s_area = 0.0;  ///< m^2
  bool grazed = false;  ///< pinned, but S has no area and no corner that could open
};

/// A face point: where the blade's outline crosses the section's side in one tet face.
struct FacePoint {
  double s = 0.0;  ///< parameter from the side's first endpoint (smaller label) to the second
  Combo combo;
  std::int32_t id = -1;  ///< its (welded) node, created on first use
};
struct FaceEntry {
  std::vector<FacePoint> points;  ///< by increasing s
};
struct FaceKeyHash {
  std::size_t operator()(const FaceKey& k) const {
    std::uint64_t h = 1469598103934665603ull;
    for (std::int32_t v : k) h = (h ^ static_cast<std::uint32_t>(v)) * 1099511628211ull;
    return static_cast<std::size_t>(h);
  }
};
template <class T>
using FaceMap = std::unordered_map<FaceKey, T, FaceKeyHash>;

/// A vertex of a tet's section: a coplanar node or a cut point on a crossing edge.
struct SecVert {
  std::uint64_t label = 0;  ///< edge_key(a, a) for node a, edge_key(a, b) for edge (a, b)
  std::array<std::int32_t, 2> support{-1, -1};  ///< node a (and b), global ids
  Combo combo;
  V2 p2 = V2::Zero();   ///< in-plane coordinates, m
  bool inside = false;  ///< inside the polygon grown by tol
  bool strict = false;  ///< inside by more than tol (may open)
};

/// A corner of the part of a coplanar face under the blade.
struct ClipCorner {
  enum class Kind {
    kNode,         ///< node key[a] of the face
    kEdgePoint,    ///< crossing b of the face's edge a (kFaceEdges[a] of the sorted key)
    kBladeCorner,  ///< the blade's corner a
  } kind = Kind::kNode;
  int a = 0, b = 0;
  Combo combo;
  V2 p2 = V2::Zero();  ///< in-plane coordinates, m
};
/// A welded coplanar face partly under the blade: the corners of face ∩ blade, counter-clockwise.
struct ClipFace {
  std::vector<ClipCorner> corners;
};
/// A point where the blade's outline crosses a coplanar edge (welded, shared by every tet
/// around the edge).
struct CopPoint {
  double s = 0.0;  ///< from the smaller node id to the larger
  Combo combo;
  std::int32_t id = -1;  ///< its node, created on first use
};
/// The edges of a face as index pairs into its sorted key.
inline constexpr std::array<std::array<int, 2>, 3> kFaceEdges{{{0, 1}, {0, 2}, {1, 2}}};

/// A point of a coplanar face's triangulation.
struct CopFacePoint {
  Combo combo;
  std::int32_t node = -1;           ///< original node (resolved per side), else -1
  std::int32_t pos = -1, neg = -1;  ///< new nodes (pos == neg when welded)
};
struct CopFaceTris {
  std::vector<CopFacePoint> pts;
  std::vector<std::array<int, 3>> tris;  ///< indices into pts
};

/// Everything one cut needs while it builds the delta. Node and tet ids are the mesh's;
/// "candidate index" ci indexes cands and tets.
struct CutState {
  /// fixed_tol > 0: classify with this tolerance (m) instead of one from the local edge length
  /// (the second pass uses the first's).
  CutState(const TetMesh& mesh_, const ConvexPolygon& blade_, const CutOptions& options_,
           const TetBoxQuery& query_, double fixed_tol_)
      : mesh(mesh_),
        blade(blade_),
        options(options_),
        query(query_),
        weld(mesh_.num_nodes()),
        fixed_tol(fixed_tol_ > 0.0 ? fixed_tol_ : options_.tolerance_m) {
    for (const Vec3& p : blade_.points()) blade2.push_back(blade_.to_plane(p));
  }

  const TetMesh& mesh;
  const ConvexPolygon& blade;
  const CutOptions& options;
  const TetBoxQuery& query;
  WeldMap weld;
  CutResult result;
  double tol = 0.0;        ///< the classification tolerance, m
  double fixed_tol = 0.0;  ///< when > 0, tol (m); else tol comes from the local edge length
  std::vector<V2> blade2;  ///< (k) the blade's corners in plane coordinates, m
  std::vector<std::int32_t> cands;                    ///< candidate tet ids, ascending
  std::vector<TetInfo> tets;                          ///< per candidate
  std::unordered_map<std::int32_t, NodeInfo> nodes;   ///< nodes of the candidates
  std::unordered_map<std::uint64_t, EdgeInfo> edges;  ///< crossing edges of straddling tets
  FaceMap<FaceEntry> faces;  ///< tet faces -> face points of the section side in them
  std::unordered_map<std::int32_t, std::vector<std::int32_t>>
      zero_tets;             ///< coplanar node -> candidate indices of the tets holding it
  FaceMap<int> coplanar;     ///< coplanar faces of the candidates -> how many candidates hold them
  FaceMap<ClipFace> pfaces;  ///< welded coplanar faces partly under the blade
  std::unordered_map<std::uint64_t, std::vector<CopPoint>> cop_edges;  ///< coplanar edges
  std::vector<std::uint64_t> front_edges;  ///< coplanar section sides the outline crosses
  FaceMap<CopFaceTris> cop_faces;          ///< triangulations of split coplanar faces
  std::vector<CopPoint> no_points;         ///< always empty
};

/// One pass of the cut (cut_mesh.cpp): every step above in order, without the second pass.
[[nodiscard]] CutResult cut_pass(const TetMesh& mesh, const ConvexPolygon& blade,
                                 const CutOptions& options, const TetBoxQuery& query,
                                 double fixed_tol = 0.0);

// ---- small helpers every step uses ------------------------------------------------------------

/// Sorted node ids of face f (local node triple) of tet t.
inline FaceKey face_key(const Tet& t, const std::array<int, 3>& f) {
  FaceKey key{t[f[0]], t[f[1]], t[f[2]]};
  std::sort(key.begin(), key.end());
  return key;
}

/// Face f of the tet lies in the plane (all three nodes coplanar).
inline bool coplanar_face(const TetInfo& info, const std::array<int, 3>& f) {
  return info.sign[f[0]] == Sign::kZero && info.sign[f[1]] == Sign::kZero &&
         info.sign[f[2]] == Sign::kZero;
}

/// Local edge (i, j) of the tet crosses the plane (one end +, the other -).
inline bool crossing_edge(const TetInfo& info, int i, int j) {
  return static_cast<int>(info.sign[i]) * static_cast<int>(info.sign[j]) < 0;
}

/// Affine coordinates of a point in face `key` (sorted): the weights of its 2nd and 3rd node.
inline V2 face_uv(const Combo& c, const FaceKey& key) {
  double w1 = 0.0, w2 = 0.0;
  for (int l = 0; l < c.count; ++l) {
    if (c.nodes[l] == key[1]) w1 += c.w[l];
    if (c.nodes[l] == key[2]) w2 += c.w[l];
  }
  return {w1, w2};
}

/// Sorts `items` counter-clockwise by angle around their centroid (p2(item): plane
/// coordinates, m) and returns the centroid.
template <class T, class P2>
V2 sort_ccw(std::vector<T>& items, P2 p2) {
  V2 c = V2::Zero();
  for (const T& item : items) c += p2(item);
  c /= static_cast<double>(items.size());
  std::sort(items.begin(), items.end(), [&](const T& a, const T& b) {
    return std::atan2(p2(a).y() - c.y(), p2(a).x() - c.x()) <
           std::atan2(p2(b).y() - c.y(), p2(b).x() - c.x());
  });
  return c;
}

/// Signed area (m^2) of the polygon `items` (counter-clockwise) as the fan from c.
template <class T, class P2>
double fan_area_from(const V2& c, const std::vector<T>& items, P2 p2) {
  double area = 0.0;
  const std::size_t n = items.size();
  for (std::size_t k = 0; k < n; ++k) area += area2d(c, p2(items[k]), p2(items[(k + 1) % n]));
  return area;
}

/// Parameters s in (0, 1) where the blade's outline crosses the 2D segment [u, w] (plane
/// coordinates, m), more than tol from its ends and from each other, ascending.
[[nodiscard]] std::vector<double> outline_crossings(const CutState& cs, const V2& u, const V2& w);

/// Id of original node v on side pos (its clone on the positive side, when it has one).
inline std::int32_t node_id(const CutState& cs, std::int32_t v, bool pos) {
  if (pos)
    if (auto cl = cs.weld.find_clone(v)) return *cl;
  return v;
}

}  // namespace serosa::cutting::detail

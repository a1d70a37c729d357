// cut_mesh: the paper's pattern-based scissor cut.
//
// Design note (the paper's figures are missing; this is what the code does and why)
// ------------------------------------------------------------------------------
// 1. Classification. Each node of a candidate tet gets phi = n . x - d against the blade's plane
//    and a sign +, 0 or - with the tolerance tol = classify_rel * h, h the longest edge of the
//    tets whose boxes meet the blade's box. The sign is a property of the node (computed once
//    per cut), never of a tet, so every tet sharing a node agrees on it. A tet's four signs give
//    one of 3^4 = 81 codes.
// 2. Case table (cutting/case_table.h). Every code maps to one of the paper's seven canonical
//    cases, plus "untouched" (+,+,+,+) and "degenerate" (0,0,0,0), through an EVEN permutation
//    of the tet's nodes (so the canonical tet keeps the positive orientation) and a mirror flag
//    (swap + and -). An even permutation always exists: four nodes and three signs means two
//    nodes share a sign, and swapping them fixes the parity.
//        kOneThree     (+,-,-,-)  tet (0, e01, e02, e03) | prism (1,2,3 / e01,e02,e03)
//        kTwoTwo       (+,+,-,-)  prism (0,e02,e03 / 1,e12,e13) | prism (2,e02,e12 / 3,e03,e13)
//        kOneZeroSplit (0,+,-,-)  tet (0, 1, e12, e13) | pyramid (2, 3, e13, e12; apex 0)
//        kTwoZeroSplit (0,0,+,-)  tet (0, 1, 2, e23) | tet (0, 1, e23, 3)
//        kOneZeroSame, kTwoZeroSame, kThreeZero: the tet whole (the "clipping" cases: only the
//        coplanar nodes inside the polygon change, to their clones on the positive side)
//    (eij: the cut point on canonical edge i-j; left of "|" the positive side, right the
//    negative; a mirrored case swaps the sides.) Pieces are exactly the tet cut by the plane of
//    the linearly interpolated phi, so they are convex and cover the tet without overlap: volume
//    is conserved to rounding and, since cut points sit strictly inside edges (|phi| > tol at
//    both ends), every piece has positive volume.
// 3. Primitives to tets (cutting/subdivide.h): prisms and pyramids use paper Tables 1 and 2 with
//    the Figure 9 selectors: every quad is cut by its diagonal through the smallest node id.
//    Every quad lies in one face of the original tet (or in the cut section), and the rule
//    depends only on the quad's four ids, so both tets sharing a face cut it the same way. The
//    two Schönhardt prisms (all three diagonals turning the same way) get a Steiner point at
//    the mean of their six nodes, expressed through the original tet's four nodes.
// 4. Welding (cutting/weld_map.h): a cut edge gets two nodes at the same place, one for each
//    side, keyed by the edge, so every tet around it uses the same pair. A coplanar node inside
//    the polygon is cloned: the original stays with the negative side, the clone goes to the
//    positive side (paper convention).
// 5. Complete or partial. A crossing edge gets a cut point iff the point lies inside the polygon
//    grown by tol (a property of the edge, so every tet around it agrees); it opens (two nodes)
//    iff it lies inside by more than tol and no "pinned" tet (below) holds the edge. A coplanar
//    node is cloned iff it lies inside the grown polygon, no pinned tet holds it, every coplanar
//    face around it that is still welded (shared by two tets) lies inside or is clipped with
//    its corner at the node under the blade (below), every partial tet
//    holding it has both its section sides from the node starting inside the blade, no flat
//    tet holds it, and both sides use it. So a node on the blade's outline opens when the far
//    side is already open: a scissors closing in many thin steps, each step's trailing edge on
//    the previous step's crack front (its apex and face points), carries the crack on.
//    A straddling tet is complete when its whole section (the polygon Sigma of its cut points
//    and coplanar nodes) lies in the grown polygon; it takes the patterns of point 2. Otherwise
//    the blade's edge ends inside it (partial cut; the paper's end cases), and the crack in it
//    is cut along S = Sigma ∩ blade (convex):
//      - face points: where the blade's outline crosses the section's side in a tet face (the
//        "blade crosses a face without cutting its edges" case), one welded node each, computed
//        once per face (keyed by the face) so both tets sharing the face agree;
//      - tip points: the blade's corners strictly inside Sigma, one welded node each;
//      - every face of the tet is triangulated so that both tets sharing it agree (split_face,
//        the patterns' rule, or, with face points, a constrained triangulation with the
//        section side's parts under the blade as edges: cutting/section_triangulation.h), and
//        the tet is coned from one welded apex on the plane. The crack in the tet is then the
//        fan from the apex over S's sides on the tet's faces (its "runs") that have an end that
//        opens; it lies in S since S is convex and the apex is in S.
//      - The apex: the midpoint of the front when S has one side across the section, the
//        blade's corner when two front sides meet there; the fan is then exactly S. Otherwise
//        (S a strip with two fronts, two or more blade corners in the tet, fronts meeting on the
//        section's boundary) no point touches every front side: the apex is the front-side
//        midpoint or blade corner whose fan covers most of S, and the crack misses the rest of
//        S in this tet (CutStats::tets_short). So does a tet whose runs have no end that opens
//        (a blade too small to cut an edge: only face points and tip points on its outline).
//      - S with no area (the blade grazes the tet: a point or a segment of Sigma on the
//        outline): split welded, coned from the tet's centroid (tets_grazed).
//    A straddling tet whose section side lies along a coplanar EDGE (two nodes on the plane)
//    that the blade's outline crosses: the crossings become welded nodes on that edge (cop_edge,
//    keyed by the edge, so every tet around it splits there: one-sided ones are fanned from
//    their opposite edge, faces holding the edge are fanned from their third node), and they
//    are corners of S like face points, so the crack stops exactly on the outline there too.
//    A tet that cannot stop the crack is "pinned": split the same way but coned from its
//    centroid with every node welded, its edges and nodes welded in its neighbours too
//    (tets_pinned). That is a tet whose section is not a convex polygon in rounding (a sliver),
//    one whose S has no area but holds a corner strictly inside the blade, and one whose
//    coplanar edge has one end strictly inside and the other outside with no crossing found
//    more than tol from both (rounding).
//    A stroke of thin steps, each cut here into the previous steps' pieces, pins tets no later
//    step covers again and re-splits the pieces ahead of its front: cut such strokes with
//    cutting/progressive_cut.h, which re-cuts the pre-stroke tets by the region swept so far.
//    A straddling tet the blade does not meet is left whole.
//    Coplanar faces partly under the blade (the paper's coplanar-face clipping, decide_faces): a
//    face lying in the plane, still welded, that the blade covers only partly (with positive
//    area) is clipped along the blade's outline: the outline's crossings of its edges become
//    welded nodes (keyed by the edge, so every tet around the edge splits there: one-sided tets
//    holding the face are coned from their off-plane node over the face's triangulation, those
//    holding only the edge are fanned from the opposite edge, straddling ones stop S there as
//    above), and the part under the blade is fanned from an opened pair of nodes at its
//    centroid. So a scissors closing in steps thinner than the grid's faces opens the crack step
//    by step.
// 6. Output: the touched tets (cut, or one-sided tets that take a clone) are removed, their
//    pieces added with the same group, each piece oriented positively by its rest volume.
// 7. Second pass (CutOptions::reopen_pinned, off by default). A pinned tet whose S has area, and
//    a partial tet whose fan would miss part of S (counting only runs with an end strictly inside
//    the blade), is coned (still welded) from S's centre c instead: c lies on the plane,
//    strictly inside the blade, so every piece has c as a coplanar node inside the blade and a
//    section that is a triangle from c (one front at most) or a fan face (c, p, q) in the plane.
//    The tets whose boxes meet the grown blade box are then rebuilt as a small local mesh after
//    the first delta and cut again by the same blade with the same tolerance: c is cloned, the
//    fan faces are clipped along the outline, the straddling pieces are cut as partial tets with
//    one front, and what the first pass already opened is left alone (there is no third pass:
//    a piece the second pass cannot open fully is fanned as in point 5). The deltas are composed
//    into one against the input mesh (new nodes' parents flattened to its nodes; every point of a
//    pinned tet is a combination of its four). Where the composition is impossible (more than
//    four parents, or an unused node) the first pass's delta is kept and second_pass_failed set.
#include "cutting/cut_mesh.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "cutting/patterns.h"
#include "cutting/section_triangulation.h"
#include "cutting/subdivide.h"
#include "cutting/tet_extent.h"
#include "cutting/weld_map.h"

namespace serosa::cutting {
namespace {

using V2 = Eigen::Vector2d;

// Faces of a tet as local node triples.
constexpr std::array<std::array<int, 3>, 4> kFaces{{{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}}};

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

// A point of a piece as a combination of original nodes (the weights apply() uses).
struct Combo {
  std::array<std::int32_t, 4> nodes{-1, -1, -1, -1};
  std::array<double, 4> w{0.0, 0.0, 0.0, 0.0};
  int count = 0;
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
  void add(const Combo& o, double scale) {
    for (int k = 0; k < o.count; ++k) add(o.nodes[k], o.w[k] * scale);
  }
  [[nodiscard]] Vec3 rest(const TetMesh& m) const {
    Vec3 r = Vec3::Zero();
    for (int k = 0; k < count; ++k) r += w[k] * m.rest[nodes[k]];
    return r;
  }
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

// A corner of S that may open: a coplanar node (node >= 0) or a cut point (edge != 0); face
// points and blade corners (neither) are welded.
struct OpenKey {
  std::int32_t node = -1;
  std::uint64_t edge = 0;
};
// A side of S on the section's boundary (a "run"), in plane coordinates (m).
struct RunSide {
  V2 a = V2::Zero(), b = V2::Zero();
  OpenKey ka, kb;
};

struct TetInfo {
  std::array<Sign, 4> sign{};
  int code = 0;
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

// A face point: where the blade's outline crosses the section's side in one tet face.
struct FacePoint {
  double s = 0.0;  ///< parameter from the side's first endpoint (smaller label) to the second
  Combo combo;
  std::int32_t id = -1;  ///< its (welded) node, created on first use
};
struct FaceEntry {
  std::vector<FacePoint> points;  ///< by increasing s
};
struct FaceKeyHash {
  std::size_t operator()(const std::array<std::int32_t, 3>& k) const {
    std::uint64_t h = 1469598103934665603ull;
    for (std::int32_t v : k) h = (h ^ static_cast<std::uint32_t>(v)) * 1099511628211ull;
    return static_cast<std::size_t>(h);
  }
};

// A vertex of a tet's section: a coplanar node or a cut point on a crossing edge.
struct SecVert {
  std::uint64_t label = 0;  ///< edge_key(a, a) for node a, edge_key(a, b) for edge (a, b)
  std::array<std::int32_t, 2> support{-1, -1};  ///< node a (and b), global ids
  Combo combo;
  V2 p2 = V2::Zero();   ///< in-plane coordinates, m
  bool inside = false;  ///< inside the polygon grown by tol
  bool strict = false;  ///< inside by more than tol (may open)
};

// Everything one cut needs while it builds the delta.
class Cutter {
 public:
  // fixed_tol > 0: classify with this tolerance (m) instead of one from the local edge length
  // (the second pass uses the first's).
  Cutter(const TetMesh& mesh, const ConvexPolygon& blade, const CutOptions& options,
         const TetBoxQuery& query, double fixed_tol = 0.0)
      : m_mesh(mesh),
        m_blade(blade),
        m_options(options),
        m_query(query),
        m_weld(mesh.num_nodes()),
        m_fixed_tol(fixed_tol > 0.0 ? fixed_tol : options.tolerance_m) {
    for (const Vec3& p : blade.points()) m_blade2.push_back(blade.to_plane(p));
  }

  CutResult run() {
    if (!find_candidates()) return std::move(m_result);
    classify();
    decide_faces();
    decide_edges();
    decide_clones();
    emit();
    return std::move(m_result);
  }

 private:
  // Candidate tets: boxes meeting the blade's box, then grown by twice the tolerance so that
  // every tet around a node or cut point within tolerance of the polygon is found.
  bool find_candidates() {
    std::vector<std::int32_t> first;
    m_query(m_blade.box_min(), m_blade.box_max(), first);
    if (first.empty()) return false;
    const double h = longest_edge_m(m_mesh, first);
    m_tol = m_fixed_tol > 0.0 ? m_fixed_tol : m_options.classify_rel * h;
    m_result.stats.tolerance_m = m_tol;
    const Vec3 grow = Vec3::Constant(2.0 * m_tol);
    m_query(m_blade.box_min() - grow, m_blade.box_max() + grow, m_cands);
    std::sort(m_cands.begin(), m_cands.end());
    m_cands.erase(std::unique(m_cands.begin(), m_cands.end()), m_cands.end());
    m_result.stats.candidates = static_cast<std::int64_t>(m_cands.size());
    return !m_cands.empty();
  }

  // Signs of nodes (once per node), cases of tets, cut points of crossing edges.
  void classify() {
    CutStats& st = m_result.stats;
    m_tets.resize(m_cands.size());
    for (std::size_t ci = 0; ci < m_cands.size(); ++ci) {
      const Tet& t = m_mesh.tets[m_cands[ci]];
      TetInfo& info = m_tets[ci];
      bool pos = false, neg = false;
      for (int k = 0; k < 4; ++k) {
        const NodeInfo& n = node(t[k]);
        info.sign[k] = n.sign;
        pos = pos || n.sign == Sign::kPos;
        neg = neg || n.sign == Sign::kNeg;
        if (n.sign == Sign::kZero) m_zero_tets[t[k]].push_back(static_cast<std::int32_t>(ci));
      }
      info.code = case_code(info.sign);
      info.straddles = pos && neg;
      ++st.per_code[info.code];
      ++st.per_case[static_cast<int>(case_table()[info.code].canonical)];
      if (!info.straddles) continue;
      // Geometrically complete: every cut point and coplanar node inside the polygon.
      bool complete = true;
      std::array<int, 2> zeros{-1, -1};
      int nz = 0;
      for (int i = 0; i < 4; ++i) {
        if (info.sign[i] == Sign::kZero) {
          complete = complete && m_nodes[t[i]].inside;
          zeros[static_cast<std::size_t>(nz++)] = i;
        }
        for (int j = i + 1; j < 4; ++j) {
          if (static_cast<int>(info.sign[i]) * static_cast<int>(info.sign[j]) >= 0) continue;
          EdgeInfo& e = edge(t[i], t[j]);
          e.tets.push_back(static_cast<std::int32_t>(ci));
          complete = complete && e.inside;
        }
      }
      info.complete = complete;
      // Where the outline crosses the section's side along a coplanar edge, the crossings
      // become welded nodes on the edge (cop_edge), shared by every tet around it, and the crack
      // stops there (analyse_partial). Pinned only when one end is strictly inside, the other
      // outside, and no crossing lies more than tol from both.
      if (!complete && nz == 2) {
        const std::int32_t a = t[zeros[0]], b = t[zeros[1]];
        const NodeInfo &na = m_nodes[a], &nb = m_nodes[b];
        if (!(na.inside && nb.inside)) {
          if (!cop_edge(a, b).empty()) {
            m_front_edges.push_back(edge_key(a, b));
          } else {
            info.pinned = na.strict || nb.strict;
          }
        }
      }
      if (!complete) analyse_partial(t, info);
    }
  }

  const NodeInfo& node(std::int32_t id) {
    auto [it, fresh] = m_nodes.try_emplace(id);
    if (fresh) {
      NodeInfo& n = it->second;
      n.phi = m_blade.signed_distance(m_mesh.x[id]);
      n.sign = n.phi > m_tol ? Sign::kPos : n.phi < -m_tol ? Sign::kNeg : Sign::kZero;
      if (n.sign == Sign::kZero) {
        n.margin = m_blade.inside_margin(m_mesh.x[id]);
        n.inside = n.margin >= -m_tol;
        n.strict = n.margin > m_tol;
      }
    }
    return it->second;
  }

  EdgeInfo& edge(std::int32_t a, std::int32_t b) {
    auto [it, fresh] = m_edges.try_emplace(edge_key(a, b));
    if (fresh) {
      const std::int32_t lo = std::min(a, b), hi = std::max(a, b);
      const double plo = m_nodes[lo].phi, phi_hi = m_nodes[hi].phi;
      it->second.t = plo / (plo - phi_hi);
      const Vec3 p = m_mesh.x[lo] + it->second.t * (m_mesh.x[hi] - m_mesh.x[lo]);
      const double margin = m_blade.inside_margin(p);
      it->second.inside = margin >= -m_tol;
      it->second.strict = margin > m_tol;
    }
    return it->second;
  }

  // Parameters s in (0, 1) where the blade's outline crosses the 2D segment [u, w], more than
  // tol from its ends and from each other, ascending.
  std::vector<double> crossings(const V2& u, const V2& w) const {
    std::vector<double> out;
    const V2 d = w - u;
    const double len = d.norm();
    if (!(len > 2.0 * m_tol)) return out;
    const std::size_t k = m_blade2.size();
    for (std::size_t i = 0; i < k; ++i) {
      const V2& b0 = m_blade2[i];
      const V2 e = m_blade2[(i + 1) % k] - b0;
      const double den = d.x() * e.y() - d.y() * e.x();
      if (std::abs(den) <= 1e-14 * len * e.norm()) continue;  // parallel
      const V2 r0 = b0 - u;
      const double s = (r0.x() * e.y() - r0.y() * e.x()) / den;
      const double r = (r0.x() * d.y() - r0.y() * d.x()) / den;
      if (r < -1e-12 || r > 1.0 + 1e-12) continue;
      if (s * len <= m_tol || (1.0 - s) * len <= m_tol) continue;
      out.push_back(s);
    }
    std::sort(out.begin(), out.end());
    std::vector<double> merged;
    for (double s : out)
      if (merged.empty() || (s - merged.back()) * len > m_tol) merged.push_back(s);
    return merged;
  }

  // ---- coplanar faces partly under the blade (the paper's coplanar-face clipping) -----------

  // A corner of the part of a coplanar face under the blade: node key[a], point b of the face's
  // edge a (edges (0,1), (0,2), (1,2) of the sorted key), or the blade's corner a.
  struct ClipCorner {
    int kind = 0;  ///< 0 node, 1 edge point, 2 blade corner
    int a = 0, b = 0;
    Combo combo;
    V2 p2 = V2::Zero();
  };
  // A welded coplanar face partly under the blade: the corners of face ∩ blade, counter-clockwise.
  struct ClipFace {
    std::vector<ClipCorner> corners;
  };
  // A point where the blade's outline crosses a coplanar edge (welded, shared by every tet
  // around the edge).
  struct CopPoint {
    double s = 0.0;  ///< from the smaller node id to the larger
    Combo combo;
    std::int32_t id = -1;
  };
  static constexpr std::array<std::array<int, 2>, 3> kFaceEdges{{{0, 1}, {0, 2}, {1, 2}}};

  // Points where the outline crosses coplanar edge (a, b), computed once per edge.
  std::vector<CopPoint>& cop_edge(std::int32_t a, std::int32_t b) {
    auto [it, fresh] = m_cop_edges.try_emplace(edge_key(a, b));
    if (fresh) {
      const std::int32_t lo = std::min(a, b), hi = std::max(a, b);
      for (double s : crossings(m_blade.to_plane(m_mesh.x[lo]), m_blade.to_plane(m_mesh.x[hi]))) {
        CopPoint p;
        p.s = s;
        p.combo.add(lo, 1.0 - s);
        p.combo.add(hi, s);
        it->second.push_back(p);
      }
    }
    return it->second;
  }
  // The crossings of coplanar edge (a, b) decided by decide_faces (empty for other edges).
  std::vector<CopPoint>& cop_points(std::int32_t a, std::int32_t b) {
    const auto it = m_cop_edges.find(edge_key(a, b));
    return it == m_cop_edges.end() ? m_no_points : it->second;
  }
  [[nodiscard]] bool has_cop_points(std::int32_t a, std::int32_t b) const {
    const auto it = m_cop_edges.find(edge_key(a, b));
    return it != m_cop_edges.end() && !it->second.empty();
  }
  std::int32_t cop_point_id(CopPoint& p) {
    if (p.id < 0) {
      p.id = m_weld.add_point(p.combo.parent());
      ++m_result.stats.face_points;
    }
    return p.id;
  }

  // Coplanar faces of the candidates (a face two candidates share is still welded; one a single
  // candidate holds is already open or on the surface); the welded ones the blade covers only
  // partly (with positive area) are clipped along its outline: their edges get the outline's
  // crossings, every tet around such an edge is split there; so are the coplanar edges along
  // partial tets' sections that the outline crosses (classify).
  void decide_faces() {
    for (const auto& [id, tets] : m_zero_tets)
      for (std::int32_t ci : tets) {
        const TetInfo& info = m_tets[static_cast<std::size_t>(ci)];
        const Tet& t = m_mesh.tets[m_cands[static_cast<std::size_t>(ci)]];
        for (const auto& f : kFaces) {
          std::array<std::int32_t, 3> key{t[f[0]], t[f[1]], t[f[2]]};
          if (info.sign[f[0]] != Sign::kZero || info.sign[f[1]] != Sign::kZero ||
              info.sign[f[2]] != Sign::kZero || std::min({key[0], key[1], key[2]}) != id)
            continue;  // counted once, from its smallest node
          std::sort(key.begin(), key.end());
          ++m_coplanar[key];
        }
      }
    std::vector<std::array<std::int32_t, 3>> keys;
    for (const auto& [key, count] : m_coplanar)
      if (count >= 2) keys.push_back(key);
    std::sort(keys.begin(), keys.end());
    for (const auto& key : keys) {
      if (m_nodes[key[0]].inside && m_nodes[key[1]].inside && m_nodes[key[2]].inside) continue;
      std::array<V2, 3> q{m_blade.to_plane(m_mesh.x[key[0]]), m_blade.to_plane(m_mesh.x[key[1]]),
                          m_blade.to_plane(m_mesh.x[key[2]])};
      const double a2 = area2d(q[0], q[1], q[2]);
      if (!(std::abs(a2) > 0.0)) continue;
      ClipFace cf;
      for (int k = 0; k < 3; ++k)
        if (m_nodes[key[static_cast<std::size_t>(k)]].inside) {
          ClipCorner c;
          c.kind = 0;
          c.a = k;
          c.combo.add(key[static_cast<std::size_t>(k)], 1.0);
          c.p2 = q[static_cast<std::size_t>(k)];
          cf.corners.push_back(c);
        }
      for (int e = 0; e < 3; ++e) {
        const auto& fe = kFaceEdges[static_cast<std::size_t>(e)];
        const std::vector<CopPoint>& pts = cop_edge(key[fe[0]], key[fe[1]]);
        for (std::size_t k = 0; k < pts.size(); ++k) {
          ClipCorner c;
          c.kind = 1;
          c.a = e;
          c.b = static_cast<int>(k);
          c.combo = pts[k].combo;
          c.p2 = (1.0 - pts[k].s) * q[fe[0]] + pts[k].s * q[fe[1]];
          cf.corners.push_back(c);
        }
      }
      double diam = 0.0;
      for (int k = 0; k < 3; ++k)
        diam = std::max(diam, (q[static_cast<std::size_t>(k)] - q[(k + 1) % 3]).norm());
      for (std::size_t k = 0; k < m_blade2.size(); ++k) {
        double margin = std::numeric_limits<double>::infinity();
        std::array<double, 3> w{};
        for (int i = 0; i < 3; ++i) {
          const V2 &u = q[static_cast<std::size_t>(i)], &v = q[(i + 1) % 3];
          const double ar = area2d(u, v, m_blade2[k]);
          margin = std::min(margin, (a2 > 0.0 ? 2.0 : -2.0) * ar / (v - u).norm());
          w[(i + 2) % 3] = ar / a2;
        }
        if (!(margin > m_tol)) continue;
        ClipCorner c;
        c.kind = 2;
        c.a = static_cast<int>(k);
        for (int i = 0; i < 3; ++i)
          c.combo.add(key[static_cast<std::size_t>(i)], w[static_cast<std::size_t>(i)]);
        c.p2 = m_blade2[k];
        cf.corners.push_back(c);
      }
      if (cf.corners.size() < 3) continue;
      V2 c = V2::Zero();
      for (const ClipCorner& cc : cf.corners) c += cc.p2;
      c /= static_cast<double>(cf.corners.size());
      std::sort(cf.corners.begin(), cf.corners.end(),
                [&](const ClipCorner& x, const ClipCorner& y) {
                  return std::atan2(x.p2.y() - c.y(), x.p2.x() - c.x()) <
                         std::atan2(y.p2.y() - c.y(), y.p2.x() - c.x());
                });
      double area = 0.0;
      const std::size_t n = cf.corners.size();
      for (std::size_t k = 0; k < n; ++k)
        area += area2d(c, cf.corners[k].p2, cf.corners[(k + 1) % n].p2);
      if (!(area > m_tol * diam)) continue;
      m_pfaces.emplace(key, std::move(cf));
    }
    // Only the edges of clipped faces, and the coplanar section sides partial tets stop the
    // crack on (classify), are split.
    std::unordered_map<std::uint64_t, std::vector<CopPoint>> kept;
    for (const auto& [key, cf] : m_pfaces)
      for (const auto& fe : kFaceEdges) {
        const std::uint64_t k = edge_key(key[fe[0]], key[fe[1]]);
        if (!m_cop_edges[k].empty()) kept.emplace(k, m_cop_edges[k]);
      }
    for (const std::uint64_t k : m_front_edges)
      if (!m_cop_edges[k].empty()) kept.emplace(k, m_cop_edges[k]);
    m_cop_edges = std::move(kept);
    // A partial tet holding a coplanar edge with crossings has them on its section's side
    // (analyse_partial). A complete one cannot (both ends inside the convex blade), save in
    // rounding: pinned.
    for (std::size_t ci = 0; ci < m_cands.size(); ++ci) {
      TetInfo& info = m_tets[ci];
      if (!info.straddles || !info.complete) continue;
      const Tet& t = m_mesh.tets[m_cands[ci]];
      for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j)
          if (info.sign[i] == Sign::kZero && info.sign[j] == Sign::kZero &&
              has_cop_points(t[i], t[j])) {
            info.complete = false;
            info.pinned = true;
            info.interacts = true;
          }
    }
  }

  // Clipped face `key` (in m_pfaces) seen from its node a: its corner at a lies under the blade
  // (the midpoints from a to the next point along both edges from a are inside), so every piece
  // of the face at a is under the blade and a may open.
  bool corner_inside(std::int32_t a, const std::array<std::int32_t, 3>& key) {
    for (std::int32_t w : key) {
      if (w == a) continue;
      Vec3 next = m_mesh.x[w];
      const auto it = m_cop_edges.find(edge_key(a, w));
      if (it != m_cop_edges.end() && !it->second.empty())
        next = (a < w ? it->second.front() : it->second.back()).combo.cur(m_mesh);
      if (m_blade.inside_margin(0.5 * (m_mesh.x[a] + next)) < -m_tol) return false;
    }
    return true;
  }

  // A point of a coplanar face's triangulation.
  struct CopFacePoint {
    Combo combo;
    std::int32_t node = -1;           ///< original node (resolved per side), else -1
    std::int32_t pos = -1, neg = -1;  ///< new nodes (pos == neg when welded)
  };
  struct CopFaceTris {
    std::vector<CopFacePoint> pts;
    std::vector<std::array<int, 3>> tris;
  };

  // The triangulation of coplanar face `key` (sorted), once per face so both tets holding it
  // agree: its nodes, the crossings on its edges, and, when the blade covers it partly, the part
  // under the blade fanned from an opened pair of nodes at its centroid.
  const CopFaceTris& cop_face(const std::array<std::int32_t, 3>& key) {
    auto [it, fresh] = m_cop_faces.try_emplace(key);
    if (!fresh) return it->second;
    CopFaceTris& ft = it->second;
    for (int k = 0; k < 3; ++k) {
      CopFacePoint p;
      p.node = key[static_cast<std::size_t>(k)];
      p.combo.add(p.node, 1.0);
      ft.pts.push_back(p);
    }
    std::array<std::vector<int>, 3> edge_idx;
    for (int e = 0; e < 3; ++e) {
      const auto& fe = kFaceEdges[static_cast<std::size_t>(e)];
      for (CopPoint& cp : cop_points(key[fe[0]], key[fe[1]])) {
        CopFacePoint p;
        p.combo = cp.combo;
        p.pos = p.neg = cop_point_id(cp);
        edge_idx[static_cast<std::size_t>(e)].push_back(static_cast<int>(ft.pts.size()));
        ft.pts.push_back(p);
      }
    }
    std::vector<std::array<int, 2>> constraints;
    int centre = -1;
    const auto pf = m_pfaces.find(key);
    if (pf != m_pfaces.end()) {
      std::vector<int> ring;
      Combo mean;
      const auto& corners = pf->second.corners;
      for (const ClipCorner& c : corners) {
        mean.add(c.combo, 1.0 / static_cast<double>(corners.size()));
        if (c.kind == 0) {
          ring.push_back(c.a);
        } else if (c.kind == 1) {
          ring.push_back(edge_idx[static_cast<std::size_t>(c.a)][static_cast<std::size_t>(c.b)]);
        } else {
          CopFacePoint p;
          p.combo = c.combo;
          p.pos = p.neg = m_weld.add_point(c.combo.parent());
          ++m_result.stats.face_points;
          ring.push_back(static_cast<int>(ft.pts.size()));
          ft.pts.push_back(p);
        }
      }
      CopFacePoint p;
      p.combo = mean;
      p.pos = m_weld.add_point(mean.parent());
      p.neg = m_weld.add_point(mean.parent());
      m_result.stats.steiner_points += 2;
      centre = static_cast<int>(ft.pts.size());
      ft.pts.push_back(p);
      for (std::size_t k = 0; k < ring.size(); ++k) {
        constraints.push_back({ring[k], ring[(k + 1) % ring.size()]});
        constraints.push_back({centre, ring[k]});
      }
    }
    std::vector<V2> uv;
    for (const CopFacePoint& p : ft.pts) {
      double w1 = 0.0, w2 = 0.0;
      for (int l = 0; l < p.combo.count; ++l) {
        if (p.combo.nodes[l] == key[1]) w1 += p.combo.w[l];
        if (p.combo.nodes[l] == key[2]) w2 += p.combo.w[l];
      }
      uv.emplace_back(w1, w2);
    }
    ft.tris = triangulate_section(uv, constraints, 1e-10);
    double area = 0.0;
    for (const auto& tr : ft.tris) area += area2d(uv[tr[0]], uv[tr[1]], uv[tr[2]]);
    if (!(std::abs(area - 0.5) <= 1e-9)) ++m_result.stats.degenerate_tets;
    return ft;
  }

  // A one-sided tet holding a clipped coplanar face or a coplanar edge with crossings: split
  // there (coned from its off-plane node, or fanned from its opposite edge), welded except the
  // clipped part under the blade.
  [[nodiscard]] bool needs_cop_split(const Tet& t, const TetInfo& info) const {
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j)
        if (info.sign[i] == Sign::kZero && info.sign[j] == Sign::kZero &&
            has_cop_points(t[i], t[j]))
          return true;
    for (const auto& f : kFaces) {
      if (info.sign[f[0]] != Sign::kZero || info.sign[f[1]] != Sign::kZero ||
          info.sign[f[2]] != Sign::kZero)
        continue;
      std::array<std::int32_t, 3> key{t[f[0]], t[f[1]], t[f[2]]};
      std::sort(key.begin(), key.end());
      if (m_pfaces.count(key) > 0) return true;
    }
    return false;
  }

  void emit_cop_split(const Tet& t, const TetInfo& info, std::uint16_t g) {
    bool pos = false;
    std::vector<int> zeros, others;
    for (int k = 0; k < 4; ++k) {
      pos = pos || info.sign[k] == Sign::kPos;
      (info.sign[k] == Sign::kZero ? zeros : others).push_back(k);
    }
    if (zeros.size() == 3) {
      std::array<std::int32_t, 3> key{t[zeros[0]], t[zeros[1]], t[zeros[2]]};
      std::sort(key.begin(), key.end());
      const CopFaceTris& ft = cop_face(key);
      const std::int32_t o = t[others[0]];
      Combo co;
      co.add(o, 1.0);
      for (const auto& tr : ft.tris) {
        std::array<std::int32_t, 4> ids{o, 0, 0, 0};
        for (int k = 0; k < 3; ++k) {
          const CopFacePoint& p = ft.pts[static_cast<std::size_t>(tr[static_cast<std::size_t>(k)])];
          ids[static_cast<std::size_t>(k + 1)] =
              p.node >= 0 ? node_id(p.node, pos) : (pos ? p.pos : p.neg);
        }
        emit_tet(ids,
                 {&co, &ft.pts[static_cast<std::size_t>(tr[0])].combo,
                  &ft.pts[static_cast<std::size_t>(tr[1])].combo,
                  &ft.pts[static_cast<std::size_t>(tr[2])].combo},
                 g);
      }
      return;
    }
    // One coplanar edge (a, b) with crossings: pieces (q_k, q_k+1, c, d) along it.
    const std::int32_t a = std::min(t[zeros[0]], t[zeros[1]]),
                       b = std::max(t[zeros[0]], t[zeros[1]]);
    std::vector<CopPoint>& pts = cop_points(a, b);
    std::vector<std::pair<std::int32_t, Combo>> chain;
    Combo ca, cb;
    ca.add(a, 1.0);
    cb.add(b, 1.0);
    chain.emplace_back(node_id(a, pos), ca);
    for (CopPoint& p : pts) chain.emplace_back(cop_point_id(p), p.combo);
    chain.emplace_back(node_id(b, pos), cb);
    Combo cc, cd;
    cc.add(t[others[0]], 1.0);
    cd.add(t[others[1]], 1.0);
    for (std::size_t k = 0; k + 1 < chain.size(); ++k)
      emit_tet({chain[k].first, chain[k + 1].first, t[others[0]], t[others[1]]},
               {&chain[k].second, &chain[k + 1].second, &cc, &cd}, g);
  }

  // An edge opens iff its cut point is strictly inside and no pinned tet holds it.
  void decide_edges() {
    for (auto& [key, e] : m_edges) {
      e.open = e.strict;
      for (std::int32_t ci : e.tets)
        e.open = e.open && !m_tets[static_cast<std::size_t>(ci)].pinned;
    }
  }

  // Clones of coplanar nodes (rules in the design note, point 5), in ascending node order.
  void decide_clones() {
    auto& coplanar = m_coplanar;
    std::vector<std::int32_t> zero_nodes;
    for (const auto& [id, tets] : m_zero_tets)
      if (m_nodes[id].inside) zero_nodes.push_back(id);
    std::sort(zero_nodes.begin(), zero_nodes.end());
    for (std::int32_t a : zero_nodes) {
      bool ok = true, pos_user = false, neg_user = false;
      for (std::int32_t ci : m_zero_tets[a]) {
        const TetInfo& info = m_tets[static_cast<std::size_t>(ci)];
        const Tet& t = m_mesh.tets[m_cands[static_cast<std::size_t>(ci)]];
        if (info.straddles) {
          // Complete: opened by its pattern. Partial: the crack may reach its coplanar node
          // only where both section sides from it start inside the blade (a node on the
          // outline whose far side an earlier cut already opened: a scissors' crack front).
          ok = ok && !info.pinned &&
               (info.complete || (info.interacts && sides_start_inside(t, info, a)));
          pos_user = neg_user = true;
          continue;
        }
        bool any = false;
        for (int k = 0; k < 4; ++k) {
          pos_user = pos_user || info.sign[k] == Sign::kPos;
          neg_user = neg_user || info.sign[k] == Sign::kNeg;
          any = any || info.sign[k] != Sign::kZero;
        }
        ok = ok && any;  // a flat tet (all four coplanar) pins its nodes
        // Every coplanar face around it that is still welded must lie inside the blade; faces
        // already open stay open.
        for (const auto& f : kFaces) {
          bool has_a = false, copl = true, inside = true;
          for (int k : f) {
            has_a = has_a || t[k] == a;
            copl = copl && info.sign[k] == Sign::kZero;
            inside = inside && m_nodes[t[k]].inside;
          }
          if (!has_a || !copl || inside) continue;
          std::array<std::int32_t, 3> key{t[f[0]], t[f[1]], t[f[2]]};
          std::sort(key.begin(), key.end());
          // A welded face partly under the blade is clipped along its outline (decide_faces):
          // a may open when the face's corner at a lies under the blade.
          ok = ok && (coplanar[key] < 2 || (m_pfaces.count(key) > 0 && corner_inside(a, key)));
        }
      }
      if (ok && pos_user && neg_user) {
        m_weld.clone(a);
        if (!m_nodes[a].strict) ++m_result.stats.clones_on_outline;
      }
    }
  }

  // Partial tet t with coplanar node a: both sides of its section from a start inside the
  // blade (the midpoint of a and the next point along the side: a face point or the side's
  // other end), so opening a opens only the part of the section the blade covers.
  bool sides_start_inside(const Tet& t, const TetInfo& info, std::int32_t a) {
    const std::vector<SecVert> sv = section(t, info);
    const std::size_t ns = sv.size();
    const std::uint64_t label = edge_key(a, a);
    std::size_t i = ns;
    for (std::size_t k = 0; k < ns; ++k)
      if (sv[k].label == label) i = k;
    if (i == ns || ns < 3) return false;
    const Vec3 xa = m_mesh.x[a];
    for (const SecVert* u : {&sv[(i + 1) % ns], &sv[(i + ns - 1) % ns]}) {
      const auto key = face_key_of(sv[i], *u);
      if (key[0] == -2) return false;
      Vec3 next = u->combo.cur(m_mesh);
      if (key[0] == -1 && has_cop_points(a, u->support[0])) {  // along a coplanar edge
        const std::vector<CopPoint>& pts = cop_points(a, u->support[0]);
        next = (a < u->support[0] ? pts.front() : pts.back()).combo.cur(m_mesh);
      }
      if (key[0] >= 0) {
        const auto it = m_faces.find(key);
        if (it != m_faces.end() && !it->second.points.empty()) {
          const FacePoint& fp =
              label < u->label ? it->second.points.front() : it->second.points.back();
          next = fp.combo.cur(m_mesh);
        }
      }
      if (m_blade.inside_margin(0.5 * (xa + next)) < -m_tol) return false;
    }
    return true;
  }

  // Id of original node v on side pos (its clone on the positive side).
  std::int32_t node_id(std::int32_t v, bool pos) const {
    if (pos)
      if (auto cl = m_weld.find_clone(v)) return *cl;
    return v;
  }

  // Resolves one pattern label of tet `t` (canonical order `perm`) on side `pos`.
  std::int32_t resolve(const Tet& t, const CaseEntry& c, std::uint8_t label, bool pos,
                       Combo& combo) {
    if (!is_edge_label(label)) {
      const std::int32_t v = t[c.perm[label]];
      combo.add(v, 1.0);
      return node_id(v, pos);
    }
    const auto& en = kEdgeNodes[label - 4];
    return edge_point_id(t[c.perm[en[0]]], t[c.perm[en[1]]], pos, combo);
  }

  std::int32_t edge_point_id(std::int32_t a, std::int32_t b, bool pos, Combo& combo) {
    const std::int32_t lo = std::min(a, b), hi = std::max(a, b);
    const EdgeInfo& e = m_edges[edge_key(a, b)];
    combo.add(lo, 1.0 - e.t);
    combo.add(hi, e.t);
    const EdgePair pair = m_weld.edge_point(a, b, e.t, e.open);
    return pos ? pair.pos : pair.neg;
  }

  void emit_tet(std::array<std::int32_t, 4> ids, const std::array<const Combo*, 4>& combos,
                std::uint16_t g) {
    const double vol = signed_volume(combos[0]->rest(m_mesh), combos[1]->rest(m_mesh),
                                     combos[2]->rest(m_mesh), combos[3]->rest(m_mesh));
    if (vol < 0.0) std::swap(ids[2], ids[3]);
    if (!(std::abs(vol) > 0.0)) ++m_result.stats.degenerate_tets;
    m_result.delta.added_tets.push_back({ids[0], ids[1], ids[2], ids[3]});
    m_result.delta.added_groups.push_back(g);
  }

  void emit_primitive(const Tet& t, const CaseEntry& c, const PatternPrimitive& prim,
                      std::uint16_t g) {
    const bool pos = (prim.side == Side::kPos) != c.mirrored;
    std::array<std::int32_t, 7> ids{};
    std::array<Combo, 7> combos{};
    const int n = prim.size();
    for (int k = 0; k < n; ++k) ids[k] = resolve(t, c, prim.points[k], pos, combos[k]);
    PrimitiveSplit split;
    if (prim.kind == PrimitiveKind::kTet) {
      emit_tet({ids[0], ids[1], ids[2], ids[3]}, {&combos[0], &combos[1], &combos[2], &combos[3]},
               g);
      return;
    }
    if (prim.kind == PrimitiveKind::kPyramid) {
      split = split_pyramid({ids[0], ids[1], ids[2], ids[3], ids[4]});
    } else {
      split = split_prism({ids[0], ids[1], ids[2], ids[3], ids[4], ids[5]});
      if (split.steiner) {
        // Mean of the six nodes, through the original tet's nodes.
        Combo mean;
        for (int k = 0; k < 6; ++k) mean.add(combos[k], 1.0 / 6.0);
        ids[6] = m_weld.add_point(mean.parent());
        combos[6] = mean;
        ++m_result.stats.steiner_points;
      }
    }
    for (const LocalTet& lt : split.tets)
      emit_tet({ids[lt[0]], ids[lt[1]], ids[lt[2]], ids[lt[3]]},
               {&combos[lt[0]], &combos[lt[1]], &combos[lt[2]], &combos[lt[3]]}, g);
  }

  // ---- partial cuts -------------------------------------------------------------------------

  // The section of straddling tet t: its vertices, in counter-clockwise order in the plane.
  std::vector<SecVert> section(const Tet& t, const TetInfo& info) {
    std::vector<SecVert> sv;
    for (int i = 0; i < 4; ++i) {
      if (info.sign[i] == Sign::kZero) {
        SecVert v;
        v.label = edge_key(t[i], t[i]);
        v.support = {t[i], -1};
        v.combo.add(t[i], 1.0);
        v.inside = m_nodes[t[i]].inside;
        v.strict = m_nodes[t[i]].strict;
        sv.push_back(v);
      }
      for (int j = i + 1; j < 4; ++j) {
        if (static_cast<int>(info.sign[i]) * static_cast<int>(info.sign[j]) >= 0) continue;
        const EdgeInfo& e = m_edges[edge_key(t[i], t[j])];
        SecVert v;
        v.label = edge_key(t[i], t[j]);
        v.support = {t[i], t[j]};
        v.combo.add(std::min(t[i], t[j]), 1.0 - e.t);
        v.combo.add(std::max(t[i], t[j]), e.t);
        v.inside = e.inside;
        v.strict = e.strict;
        sv.push_back(v);
      }
    }
    V2 c = V2::Zero();
    for (SecVert& v : sv) {
      v.p2 = m_blade.to_plane(v.combo.cur(m_mesh));
      c += v.p2;
    }
    c /= static_cast<double>(sv.size());
    std::sort(sv.begin(), sv.end(), [&](const SecVert& a, const SecVert& b) {
      return std::atan2(a.p2.y() - c.y(), a.p2.x() - c.x()) <
             std::atan2(b.p2.y() - c.y(), b.p2.x() - c.x());
    });
    return sv;
  }

  // Sorted node ids of the face holding section vertices u and w; {-1,..} entries when they
  // share only an edge (two coplanar nodes); {-2,-2,-2} when they share no face.
  static std::array<std::int32_t, 3> face_key_of(const SecVert& u, const SecVert& w) {
    std::array<std::int32_t, 4> ids{u.support[0], u.support[1], w.support[0], w.support[1]};
    std::sort(ids.begin(), ids.end());
    std::array<std::int32_t, 3> key{-1, -1, -1};
    int n = 0;
    for (std::int32_t v : ids)
      if (v >= 0 && (n == 0 || key[static_cast<std::size_t>(n - 1)] != v)) {
        if (n == 3) return {-2, -2, -2};
        key[static_cast<std::size_t>(n++)] = v;
      }
    if (n < 3) return {-1, -1, -1};
    return key;
  }

  // Face points of the section's side (u, w) in a tet face, computed once per face from the
  // face's own data (so both tets sharing it agree), ordered from the smaller label.
  FaceEntry& face_points(const std::array<std::int32_t, 3>& key, const SecVert& u,
                         const SecVert& w) {
    auto [it, fresh] = m_faces.try_emplace(key);
    if (fresh && !(u.inside && w.inside)) {
      const SecVert& a = u.label < w.label ? u : w;
      const SecVert& b = u.label < w.label ? w : u;
      for (double s : crossings(a.p2, b.p2)) {
        FacePoint fp;
        fp.s = s;
        fp.combo.add(a.combo, 1.0 - s);
        fp.combo.add(b.combo, s);
        it->second.points.push_back(fp);
      }
    }
    return it->second;
  }

  std::int32_t face_point_id(FacePoint& fp) {
    if (fp.id < 0) {
      fp.id = m_weld.add_point(fp.combo.parent());
      ++m_result.stats.face_points;
    }
    return fp.id;
  }

  // S's centre (the mean of its corners, which lies strictly inside S when S has area) if it lies
  // inside the blade by more than tol: a pinned tet is coned from it.
  template <class SPointVec>
  void find_centre(const SPointVec& sp, double diam, TetInfo& info) const {
    info.has_centre = false;
    if (sp.size() < 3) return;
    V2 c = V2::Zero();
    for (const auto& p : sp) c += p.p2;
    c /= static_cast<double>(sp.size());
    std::vector<V2> ring;
    for (const auto& p : sp) ring.push_back(p.p2);
    std::sort(ring.begin(), ring.end(), [&](const V2& a, const V2& b) {
      return std::atan2(a.y() - c.y(), a.x() - c.x()) < std::atan2(b.y() - c.y(), b.x() - c.x());
    });
    double area = 0.0;
    for (std::size_t k = 0; k < ring.size(); ++k)
      area += area2d(c, ring[k], ring[(k + 1) % ring.size()]);
    if (!(area > m_tol * diam)) return;
    Combo centre;
    for (const auto& p : sp) centre.add(p.combo, 1.0 / static_cast<double>(sp.size()));
    if (!(m_blade.inside_margin(centre.cur(m_mesh)) > m_tol)) return;
    info.centre = centre;
    info.has_centre = true;
  }

  // A straddling tet that is not complete: finds the face points on its faces, whether the
  // blade meets it at all, and where the crack's front runs inside it: S = section ∩ blade is
  // opened by coning every piece from one apex on the front (the midpoint of a single chord, or
  // the blade's corner where two chords meet), so the crack is exactly the fan from the apex
  // over S's sides on the tet's faces. Fronts that no single point touches (two chords apart,
  // or two of the blade's corners inside) get the apex whose fan covers most of S (design note,
  // point 5).
  void analyse_partial(const Tet& t, TetInfo& info) {
    const std::vector<SecVert> sv = section(t, info);
    const std::size_t ns = sv.size();
    struct SPoint {
      V2 p2;
      Combo combo;
      bool boundary = true;
      OpenKey key;
      bool strict = false;  ///< a section corner strictly inside the blade (may open)
    };
    std::vector<SPoint> sp;   // S's corners
    bool any_strict = false;  // a corner of S that may open
    double diam = 0.0;
    for (std::size_t i = 0; i < ns; ++i)
      for (std::size_t j = i + 1; j < ns; ++j) diam = std::max(diam, (sv[i].p2 - sv[j].p2).norm());
    for (std::size_t i = 0; i < ns; ++i) {
      const SecVert& u = sv[i];
      const SecVert& w = sv[(i + 1) % ns];
      if (u.inside) {
        any_strict = any_strict || u.strict;
        OpenKey key;
        if (u.support[1] < 0)
          key.node = u.support[0];
        else
          key.edge = u.label;
        sp.push_back({u.p2, u.combo, true, key, u.strict});
        info.interacts = true;
      }
      const auto key = face_key_of(u, w);
      if (key[0] == -2) {
        info.pinned = true;  // unordered section (a sliver): no opening here
        continue;
      }
      if (key[0] == -1) {  // along a coplanar edge: the outline's crossings of it (classify)
        const SecVert& lo = u.support[0] < w.support[0] ? u : w;
        const SecVert& hi = u.support[0] < w.support[0] ? w : u;
        const std::int32_t na = u.support[0], nb = w.support[0];
        if (m_nodes[na].inside && m_nodes[nb].inside) continue;  // no crossing (classify)
        for (const CopPoint& cp : cop_edge(na, nb)) {
          sp.push_back({lo.p2 + cp.s * (hi.p2 - lo.p2), cp.combo, true, {}, false});
          info.interacts = true;
        }
        continue;
      }
      const FaceEntry& fe = face_points(key, u, w);
      const SecVert& a = u.label < w.label ? u : w;
      const SecVert& b = u.label < w.label ? w : u;
      for (const FacePoint& fp : fe.points) {
        sp.push_back({a.p2 + fp.s * (b.p2 - a.p2), fp.combo, true, {}, false});
        info.interacts = true;
      }
    }
    for (std::size_t k = 0; k < m_blade2.size(); ++k) {
      double margin = std::numeric_limits<double>::infinity();
      for (std::size_t i = 0; i < ns; ++i) {
        const V2 e = sv[(i + 1) % ns].p2 - sv[i].p2;
        const V2 q = m_blade2[k] - sv[i].p2;
        margin = std::min(margin, (e.x() * q.y() - e.y() * q.x()) / e.norm());
      }
      if (margin > m_tol)
        sp.push_back({m_blade2[k], barycentric(t, m_blade.points()[k]), false, {}, false});
    }
    if (m_options.reopen_pinned) find_centre(sp, diam, info);
    if (info.pinned || !info.interacts) return;
    // S's corners counter-clockwise; its sides on the section's boundary ("runs") or across it
    // (the front).
    V2 c = V2::Zero();
    for (const SPoint& p : sp) c += p.p2;
    c /= static_cast<double>(sp.size());
    std::sort(sp.begin(), sp.end(), [&](const SPoint& a, const SPoint& b) {
      return std::atan2(a.p2.y() - c.y(), a.p2.x() - c.x()) <
             std::atan2(b.p2.y() - c.y(), b.p2.x() - c.x());
    });
    const std::size_t n = sp.size();
    double area = 0.0;
    for (std::size_t k = 0; k < n; ++k) area += area2d(c, sp[k].p2, sp[(k + 1) % n].p2);
    if (n < 3 || !(area > m_tol * diam)) {
      // S has no area: nothing opens here; split welded like a pinned tet. When no corner of
      // S is strictly inside the blade, no edge or node of the tet could open anyway: the blade
      // only grazes it (a point or a segment of its section on the blade's outline).
      info.pinned = true;
      info.grazed = !any_strict;
      return;
    }
    auto on_section_boundary = [&](const V2& q) {
      for (std::size_t i = 0; i < ns; ++i) {
        const V2 e = sv[(i + 1) % ns].p2 - sv[i].p2;
        const double l2 = e.squaredNorm();
        const double s = std::clamp(e.dot(q - sv[i].p2) / l2, 0.0, 1.0);
        if ((sv[i].p2 + s * e - q).norm() <= 1e-9 * diam) return true;
      }
      return false;
    };
    std::vector<char> front(n, 0);
    std::size_t fronts = 0;
    for (std::size_t k = 0; k < n; ++k) {
      const SPoint &p = sp[k], &q = sp[(k + 1) % n];
      front[k] = !(p.boundary && q.boundary && on_section_boundary(0.5 * (p.p2 + q.p2)));
      fronts += front[k] ? 1 : 0;
    }
    // One chain of front sides: its start is a front side after a run.
    std::size_t chains = 0, first = 0;
    for (std::size_t k = 0; k < n; ++k)
      if (front[k] && !front[(k + n - 1) % n]) {
        ++chains;
        first = k;
      }
    info.s_area = area;
    for (std::size_t k = 0; k < n; ++k)
      if (!front[k])
        info.runs.push_back({sp[k].p2, sp[(k + 1) % n].p2, sp[k].key, sp[(k + 1) % n].key});
    // The fan from q over the runs with an end that may open (strictly inside): the crack, at
    // most.
    auto fan_area = [&](const V2& q) {
      double a = 0.0;
      for (std::size_t k = 0; k < n; ++k)
        if (!front[k] && (sp[k].strict || sp[(k + 1) % n].strict))
          a += area2d(q, sp[k].p2, sp[(k + 1) % n].p2);
      return a;
    };
    info.apex = Combo{};
    if (chains == 1 && fronts == 1) {
      info.apex.add(sp[first].combo, 0.5);
      info.apex.add(sp[(first + 1) % n].combo, 0.5);
      info.apex2 = 0.5 * (sp[first].p2 + sp[(first + 1) % n].p2);
    } else if (chains == 1 && fronts == 2 && !sp[(first + 1) % n].boundary) {
      info.apex = sp[(first + 1) % n].combo;
      info.apex2 = sp[(first + 1) % n].p2;
    }
    if (info.apex.count > 0 &&
        (!m_options.reopen_pinned || fan_area(info.apex2) >= (1.0 - 1e-9) * area))
      return;
    // No point touches every front side (two runs, more than two front sides, or two front
    // sides meeting on the section's boundary). The second pass, when on, cones such a tet
    // from S's centre and cuts it again; otherwise the crack here is the fan from the apex
    // that covers most of S: the midpoint of a front side or a blade corner inside the
    // section. The fan lies in S (S is convex), so the crack stays on the blade; it misses the
    // part of S beyond the front sides away from the apex (counted in tets_short).
    if (m_options.reopen_pinned && info.has_centre) {
      info.pinned = true;
      info.runs.clear();
      return;
    }
    if (info.apex.count > 0) return;
    double best = -1.0;
    for (std::size_t k = 0; k < n; ++k) {
      if (front[k]) {
        const V2 mid = 0.5 * (sp[k].p2 + sp[(k + 1) % n].p2);
        const double a = fan_area(mid);
        if (a > best) {
          best = a;
          info.apex = Combo{};
          info.apex.add(sp[k].combo, 0.5);
          info.apex.add(sp[(k + 1) % n].combo, 0.5);
          info.apex2 = mid;
        }
      }
      if (!sp[k].boundary) {
        const double a = fan_area(sp[k].p2);
        if (a > best) {
          best = a;
          info.apex = sp[k].combo;
          info.apex2 = sp[k].p2;
        }
      }
    }
  }

  // Partial tet, not pinned: whether its crack (the fan from the apex over S's runs with an end
  // that opens) misses part of S. After decide_edges and decide_clones.
  [[nodiscard]] bool crack_short(const TetInfo& info) const {
    auto opens = [&](const OpenKey& k) {
      if (k.node >= 0) return m_weld.find_clone(k.node).has_value();
      if (k.edge == 0) return false;
      const auto it = m_edges.find(k.edge);
      return it != m_edges.end() && it->second.open;
    };
    double opened = 0.0;
    for (const RunSide& r : info.runs)
      if (opens(r.ka) || opens(r.kb)) opened += area2d(info.apex2, r.a, r.b);
    return !(opened >= (1.0 - 1e-9) * info.s_area);
  }

  // Barycentric combination of tet t's nodes giving point p (current positions).
  Combo barycentric(const Tet& t, const Vec3& p) const {
    const Vec3 &a = m_mesh.x[t[0]], &b = m_mesh.x[t[1]], &c = m_mesh.x[t[2]], &d = m_mesh.x[t[3]];
    const double v = signed_volume(a, b, c, d);
    std::array<double, 4> w{signed_volume(p, b, c, d) / v, signed_volume(a, p, c, d) / v,
                            signed_volume(a, b, p, d) / v, 0.0};
    w[3] = 1.0 - w[0] - w[1] - w[2];
    Combo out;
    for (int k = 0; k < 4; ++k) out.add(t[k], w[static_cast<std::size_t>(k)]);
    return out;
  }

  // A partial (or pinned) tet: every face triangulated by the face rule, coned from the apex.
  void emit_partial(const Tet& t, const TetInfo& info, std::uint16_t g) {
    Combo apex = info.apex;
    if (info.pinned && info.has_centre) {
      apex = info.centre;
    } else if (info.pinned) {
      apex = Combo{};
      for (int k = 0; k < 4; ++k) apex.add(t[k], 0.25);
    }
    const std::int32_t aid = m_weld.add_point(apex.parent());
    ++m_result.stats.steiner_points;
    for (const auto& f : kFaces) emit_face(t, info, f, aid, apex, g);
  }

  // One point of a face's triangulation: ids on the positive and negative side.
  struct FPoint {
    Combo combo;
    std::int32_t pos = -1, neg = -1;
    Sign sign = Sign::kZero;  ///< original nodes: their sign; points on the plane: kZero
    V2 uv = V2::Zero();       ///< affine coordinates in the face (weights of its 2nd, 3rd node)
  };

  // Tet face f of a partial tet, triangulated so that both tets sharing it agree, coned from the
  // apex (aid, apex). Faces on one side: whole. Crossed faces without face points: split_face
  // (the patterns' rule) at the cut points that exist. Crossed faces with face points: the
  // constrained triangulation (cutting/section_triangulation.h) of the face's nodes, existing cut
  // points and face points, in affine coordinates from the face's sorted node ids, with the
  // section side's parts inside the blade as constraints.
  void emit_face(const Tet& t, const TetInfo& info, const std::array<int, 3>& f, std::int32_t aid,
                 const Combo& apex, std::uint16_t g) {
    std::array<Sign, 3> sg{info.sign[f[0]], info.sign[f[1]], info.sign[f[2]]};
    const bool has_pos = std::count(sg.begin(), sg.end(), Sign::kPos) > 0;
    const bool has_neg = std::count(sg.begin(), sg.end(), Sign::kNeg) > 0;
    auto node_point = [&](int k) {
      FPoint p;
      const std::int32_t v = t[f[k]];
      p.combo.add(v, 1.0);
      p.pos = node_id(v, true);
      p.neg = v;
      p.sign = sg[k];
      return p;
    };
    auto cone = [&](const FPoint& a, const FPoint& b, const FPoint& c, bool pos) {
      emit_tet({aid, pos ? a.pos : a.neg, pos ? b.pos : b.neg, pos ? c.pos : c.neg},
               {&apex, &a.combo, &b.combo, &c.combo}, g);
    };
    // Side of a triangle from its original nodes: +1, -1, or 0 when it crosses the plane.
    auto tri_side = [](const FPoint& a, const FPoint& b, const FPoint& c) {
      bool p = false, n = false;
      for (const FPoint* q : {&a, &b, &c}) {
        p = p || q->sign == Sign::kPos;
        n = n || q->sign == Sign::kNeg;
      }
      return p && n ? 0 : p ? 1 : -1;
    };
    auto emit_tri = [&](const FPoint& a, const FPoint& b, const FPoint& c) {
      const int side = tri_side(a, b, c);
      if (side == 0) {  // across the plane: only welded points may lie on it
        for (const FPoint* q : {&a, &b, &c})
          if (q->pos != q->neg) ++m_result.stats.degenerate_tets;
      }
      cone(a, b, c, side >= 0);
    };
    if (!(has_pos && has_neg)) {  // the whole face on one side
      // A coplanar edge with crossings (decide_faces): fanned from the face's third node.
      for (int k = 0; k < 3; ++k) {
        const int i = f[k], j = f[(k + 1) % 3], o = f[(k + 2) % 3];
        if (info.sign[i] != Sign::kZero || info.sign[j] != Sign::kZero ||
            !has_cop_points(t[i], t[j]))
          continue;
        const std::int32_t lo = std::min(t[i], t[j]), hi = std::max(t[i], t[j]);
        std::vector<FPoint> chain{node_point(t[i] == lo ? k : (k + 1) % 3)};
        for (CopPoint& cp : cop_points(lo, hi)) {
          FPoint p;
          p.combo = cp.combo;
          p.pos = p.neg = cop_point_id(cp);
          chain.push_back(p);
        }
        chain.push_back(node_point(t[i] == lo ? (k + 1) % 3 : k));
        const FPoint third = node_point((k + 2) % 3);
        (void)o;
        for (std::size_t l = 0; l + 1 < chain.size(); ++l) emit_tri(chain[l], chain[l + 1], third);
        return;
      }
      emit_tri(node_point(0), node_point(1), node_point(2));
      return;
    }
    // Cut points of the face's crossing edges that exist (inside the polygon).
    std::array<FPoint, 6> fp{node_point(0), node_point(1), node_point(2), {}, {}, {}};
    std::array<bool, 3> has_edge{false, false, false};
    for (int k = 0; k < 3; ++k) {
      const int i = f[k], j = f[(k + 1) % 3];
      if (static_cast<int>(info.sign[i]) * static_cast<int>(info.sign[j]) >= 0) continue;
      const EdgeInfo& e = m_edges[edge_key(t[i], t[j])];
      if (!e.inside) continue;
      has_edge[k] = true;
      FPoint& p = fp[static_cast<std::size_t>(3 + k)];
      p.pos = edge_point_id(t[i], t[j], true, p.combo);
      Combo unused;
      p.neg = edge_point_id(t[i], t[j], false, unused);
    }
    std::array<std::int32_t, 3> key{t[f[0]], t[f[1]], t[f[2]]};
    std::sort(key.begin(), key.end());
    const auto fit = m_faces.find(key);
    if (fit == m_faces.end() || fit->second.points.empty()) {
      // split_face with this side's ids, once per side; triangles across the plane from the
      // positive call.
      for (const bool pos : {true, false}) {
        std::array<std::int32_t, 6> ids{-1, -1, -1, -1, -1, -1};
        for (int k = 0; k < 6; ++k)
          if (k < 3 || has_edge[static_cast<std::size_t>(k - 3)])
            ids[static_cast<std::size_t>(k)] =
                pos ? fp[static_cast<std::size_t>(k)].pos : fp[static_cast<std::size_t>(k)].neg;
        const FaceSplit fs = split_face(ids);
        for (int k = 0; k < fs.count; ++k) {
          const auto& tr = fs.tris[static_cast<std::size_t>(k)];
          const FPoint &a = fp[tr[0]], &b = fp[tr[1]], &c = fp[tr[2]];
          const int side = tri_side(a, b, c);
          if (side == (pos ? 1 : -1) || (pos && side == 0)) emit_tri(a, b, c);
        }
      }
      return;
    }
    // With face points: affine coordinates from the sorted ids.
    std::vector<FPoint> pts;
    for (int k = 0; k < 6; ++k)
      if (k < 3 || has_edge[static_cast<std::size_t>(k - 3)])
        pts.push_back(fp[static_cast<std::size_t>(k)]);
    // The section side's endpoints (coplanar nodes or cut points) and its face points.
    std::vector<std::pair<std::uint64_t, Combo>> ends;  // (label, combo)
    for (int k = 0; k < 3; ++k) {
      const int i = f[k], j = f[(k + 1) % 3];
      if (sg[static_cast<std::size_t>(k)] == Sign::kZero) {
        Combo cz;
        cz.add(t[i], 1.0);
        ends.emplace_back(edge_key(t[i], t[i]), cz);
      }
      if (static_cast<int>(info.sign[i]) * static_cast<int>(info.sign[j]) < 0) {
        const EdgeInfo& e = m_edges[edge_key(t[i], t[j])];
        Combo ce;
        ce.add(std::min(t[i], t[j]), 1.0 - e.t);
        ce.add(std::max(t[i], t[j]), e.t);
        ends.emplace_back(edge_key(t[i], t[j]), ce);
      }
    }
    if (ends.size() != 2) {
      ++m_result.stats.degenerate_tets;
      return;
    }
    if (ends[1].first < ends[0].first) std::swap(ends[0], ends[1]);
    // Points along the side, from the smaller label: index into pts or -1 (a missing cut point).
    auto find_point = [&](const Combo& c) {
      for (std::size_t k = 0; k < pts.size(); ++k) {
        const Combo& q = pts[k].combo;
        bool same = q.count == c.count;
        for (int l = 0; l < c.count && same; ++l) {
          bool found = false;
          for (int m = 0; m < q.count; ++m)
            found = found || (q.nodes[m] == c.nodes[l] && q.w[m] == c.w[l]);
          same = found;
        }
        if (same) return static_cast<int>(k);
      }
      return -1;
    };
    std::vector<int> along{find_point(ends[0].second)};
    std::vector<Combo> along_combo{ends[0].second};
    for (FacePoint& q : fit->second.points) {
      FPoint p;
      p.combo = q.combo;
      p.pos = p.neg = face_point_id(q);
      along.push_back(static_cast<int>(pts.size()));
      along_combo.push_back(q.combo);
      pts.push_back(p);
    }
    along.push_back(find_point(ends[1].second));
    along_combo.push_back(ends[1].second);
    for (FPoint& p : pts) {
      double w1 = 0.0, w2 = 0.0;
      for (int l = 0; l < p.combo.count; ++l) {
        if (p.combo.nodes[l] == key[1]) w1 += p.combo.w[l];
        if (p.combo.nodes[l] == key[2]) w2 += p.combo.w[l];
      }
      p.uv = V2(w1, w2);
    }
    std::vector<std::array<int, 2>> constraints;
    for (std::size_t k = 0; k + 1 < along.size(); ++k) {
      if (along[k] < 0 || along[k + 1] < 0) continue;
      Combo mid;
      mid.add(along_combo[k], 0.5);
      mid.add(along_combo[k + 1], 0.5);
      if (m_blade.inside_margin(mid.cur(m_mesh)) >= 0.0)
        constraints.push_back({along[k], along[k + 1]});
    }
    std::vector<V2> uv;
    for (const FPoint& p : pts) uv.push_back(p.uv);
    const auto tris = triangulate_section(uv, constraints, 1e-10);
    double area = 0.0;
    for (const auto& tr : tris) {
      area += area2d(uv[tr[0]], uv[tr[1]], uv[tr[2]]);
      emit_tri(pts[tr[0]], pts[tr[1]], pts[tr[2]]);
    }
    if (!(std::abs(area - 0.5) <= 1e-9)) ++m_result.stats.degenerate_tets;
  }

  // Pieces of every touched tet, in ascending tet id.
  void emit() {
    CutStats& st = m_result.stats;
    TopologyDelta& d = m_result.delta;
    for (std::size_t ci = 0; ci < m_cands.size(); ++ci) {
      const TetInfo& info = m_tets[ci];
      const std::int32_t ti = m_cands[ci];
      const Tet& t = m_mesh.tets[ti];
      const CaseEntry& c = case_table()[info.code];
      if (info.straddles && !info.complete) {
        if (!info.interacts) continue;  // the blade misses it: left whole
        ++st.tets_partial;
        st.tets_pinned += info.pinned && !info.grazed ? 1 : 0;
        st.tets_grazed += info.grazed ? 1 : 0;
        st.pinned_centred += info.pinned && info.has_centre ? 1 : 0;
        st.tets_short += !info.pinned && crack_short(info) ? 1 : 0;
        d.removed_tets.push_back(ti);
        emit_partial(t, info, m_mesh.group[ti]);
        continue;
      }
      if (info.straddles) {
        ++st.tets_split;
      } else {
        // One-sided: split where it holds a clipped coplanar face or a coplanar edge with
        // crossings; else touched when on the positive side with a cloned coplanar node.
        bool pos = false, cloned = false, flat = true;
        for (int k = 0; k < 4; ++k) {
          pos = pos || info.sign[k] == Sign::kPos;
          flat = flat && info.sign[k] == Sign::kZero;
          cloned = cloned || (info.sign[k] == Sign::kZero && m_weld.find_clone(t[k]));
        }
        if (!flat && needs_cop_split(t, info)) {
          ++st.tets_split;
          d.removed_tets.push_back(ti);
          emit_cop_split(t, info, m_mesh.group[ti]);
          continue;
        }
        if (!pos || !cloned) continue;
        ++st.tets_relabelled;
      }
      ++st.split_per_case[static_cast<int>(c.canonical)];
      d.removed_tets.push_back(ti);
      for (const PatternPrimitive& prim : pattern(c.canonical))
        emit_primitive(t, c, prim, m_mesh.group[ti]);
    }
    st.tets_removed = static_cast<std::int64_t>(d.removed_tets.size());
    st.tets_added = static_cast<std::int64_t>(d.added_tets.size());
    st.edge_pairs = m_weld.edge_pairs();
    st.edge_singles = m_weld.edge_singles();
    st.clones = m_weld.clones();
    d.added_nodes = m_weld.take_new_nodes();
    st.nodes_added = static_cast<std::int64_t>(d.added_nodes.size());
  }

  const TetMesh& m_mesh;
  const ConvexPolygon& m_blade;
  const CutOptions& m_options;
  const TetBoxQuery& m_query;
  WeldMap m_weld;
  CutResult m_result;
  double m_tol = 0.0;
  double m_fixed_tol = 0.0;
  std::vector<V2> m_blade2;           ///< the blade's corners in plane coordinates, m
  std::vector<std::int32_t> m_cands;  ///< candidate tet ids, ascending
  std::vector<TetInfo> m_tets;        ///< per candidate
  std::unordered_map<std::int32_t, NodeInfo> m_nodes;
  std::unordered_map<std::uint64_t, EdgeInfo> m_edges;  ///< crossing edges of straddling tets
  std::unordered_map<std::array<std::int32_t, 3>, FaceEntry, FaceKeyHash>
      m_faces;  ///< sorted face ids -> face points of its section side
  std::unordered_map<std::int32_t, std::vector<std::int32_t>>
      m_zero_tets;  ///< coplanar node -> tets
  std::unordered_map<std::array<std::int32_t, 3>, int, FaceKeyHash>
      m_coplanar;  ///< sorted coplanar faces of the candidates -> how many candidates hold them
  std::unordered_map<std::array<std::int32_t, 3>, ClipFace, FaceKeyHash>
      m_pfaces;  ///< welded coplanar faces partly under the blade
  std::unordered_map<std::uint64_t, std::vector<CopPoint>> m_cop_edges;  ///< coplanar edges
  std::vector<std::uint64_t> m_front_edges;  ///< coplanar section sides the outline crosses
  std::unordered_map<std::array<std::int32_t, 3>, CopFaceTris, FaceKeyHash>
      m_cop_faces;                    ///< triangulations of split coplanar faces
  std::vector<CopPoint> m_no_points;  ///< always empty
};

}  // namespace

TetBoxQuery brute_force_query(const TetMesh& mesh) {
  return [&mesh](const Vec3& lo, const Vec3& hi, std::vector<std::int32_t>& out) {
    for (std::int32_t i = 0; i < mesh.num_tets(); ++i) {
      Vec3 tlo, thi;
      tet_box(mesh, mesh.tets[i], tlo, thi);
      if ((tlo.array() <= hi.array()).all() && (thi.array() >= lo.array()).all()) out.push_back(i);
    }
  };
}

namespace {

// The second pass (design note, point 7): the first pass's result is rebuilt locally (the tets
// whose boxes meet the grown blade box, after the first delta), cut again by the same blade with
// the same tolerance, and the two deltas are composed into one against `mesh`. Returns false
// (and leaves `first` as it was) when the composition is not possible: a new node whose parents,
// flattened to nodes of `mesh`, are more than four, or a node of the first pass no tet uses.
bool second_pass(const TetMesh& mesh, const ConvexPolygon& blade, const CutOptions& options,
                 const TetBoxQuery& query, CutResult& first) {
  const TopologyDelta& d1 = first.delta;
  const double tol = first.stats.tolerance_m;
  const std::int32_t n_old = mesh.num_nodes();
  const auto n1 = static_cast<std::int32_t>(d1.added_nodes.size());
  // Local mesh: original candidates the first pass kept, then the first pass's pieces.
  std::vector<std::int32_t> cands;
  const Vec3 grow = Vec3::Constant(2.0 * tol);
  query(blade.box_min() - grow, blade.box_max() + grow, cands);
  std::sort(cands.begin(), cands.end());
  cands.erase(std::unique(cands.begin(), cands.end()), cands.end());
  TetMesh local;
  std::vector<std::int32_t> global_of;                 // local node -> global id (new: n_old + k)
  std::unordered_map<std::int32_t, std::int32_t> lid;  // global id -> local node
  auto local_node = [&](std::int32_t g) {
    auto [it, fresh] = lid.try_emplace(g, static_cast<std::int32_t>(global_of.size()));
    if (fresh) {
      global_of.push_back(g);
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
      local.rest.push_back(r);
      local.x.push_back(x);
    }
    return it->second;
  };
  std::vector<std::int32_t> origin;  // local tet -> global old tet id, or -1 - (added index)
  auto add_local = [&](const Tet& t, std::uint16_t g, std::int32_t o) {
    local.tets.push_back({local_node(t[0]), local_node(t[1]), local_node(t[2]), local_node(t[3])});
    local.group.push_back(g);
    origin.push_back(o);
  };
  for (std::int32_t ti : cands)
    if (!std::binary_search(d1.removed_tets.begin(), d1.removed_tets.end(), ti))
      add_local(mesh.tets[static_cast<std::size_t>(ti)], mesh.group[static_cast<std::size_t>(ti)],
                ti);
  for (std::size_t k = 0; k < d1.added_tets.size(); ++k)
    add_local(d1.added_tets[k], d1.added_groups[k], -1 - static_cast<std::int32_t>(k));
  local.fill_node_state();
  const std::int32_t n_local = local.num_nodes();
  CutOptions once = options;  // no third pass: what the second pass cannot open, it fans
  once.reopen_pinned = false;
  const CutResult second = Cutter(local, blade, once, brute_force_query(local), tol).run();
  const TopologyDelta& d2 = second.delta;
  if (d2.empty()) return true;
  // Compose.
  TopologyDelta out;
  out.removed_tets = d1.removed_tets;
  std::vector<char> dropped(d1.added_tets.size(), 0);
  std::int64_t originals = 0;
  for (std::int32_t lt : d2.removed_tets) {
    const std::int32_t o = origin[static_cast<std::size_t>(lt)];
    if (o >= 0) {
      out.removed_tets.push_back(o);
      ++originals;
    } else {
      dropped[static_cast<std::size_t>(-1 - o)] = 1;
    }
  }
  std::sort(out.removed_tets.begin(), out.removed_tets.end());
  auto global_node = [&](std::int32_t l) {
    return l < n_local ? global_of[static_cast<std::size_t>(l)] : n_old + n1 + (l - n_local);
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
      const std::int32_t g = global_of[static_cast<std::size_t>(p.nodes[k])];
      if (g < n_old) {
        ok = add(g, p.weights[k]);
        continue;
      }
      const NodeParent& q = d1.added_nodes[static_cast<std::size_t>(g - n_old)];
      for (int l = 0; l < q.count && ok; ++l) ok = add(q.nodes[l], p.weights[k] * q.weights[l]);
    }
    // Parents with (rounding-)zero weight are dropped; more than four left cannot be stored.
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
    out.added_nodes.push_back(f);
  }
  // Every new node is used.
  std::vector<char> used(out.added_nodes.size(), 0);
  for (const Tet& t : out.added_tets)
    for (std::int32_t v : t)
      if (v >= n_old) used[static_cast<std::size_t>(v - n_old)] = 1;
  if (std::find(used.begin(), used.end(), 0) != used.end()) return false;
  CutStats st = first.stats;
  const CutStats& s2 = second.stats;
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
  first.delta = std::move(out);
  first.stats = st;
  return true;
}

}  // namespace

CutResult cut_mesh(const TetMesh& mesh, const ConvexPolygon& blade, const CutOptions& options,
                   const TetBoxQuery& query) {
  const TetBoxQuery brute = query ? TetBoxQuery{} : brute_force_query(mesh);
  const TetBoxQuery& q = query ? query : brute;
  CutResult r = Cutter(mesh, blade, options, q).run();
  if (r.stats.pinned_centred > 0 && !second_pass(mesh, blade, options, q, r))
    ++r.stats.second_pass_failed;
  return r;
}

}  // namespace serosa::cutting

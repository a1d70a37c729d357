// Partial-cut analysis (docs/cutting.md, point 5): S = section ∩ blade of a straddling tet the
// blade's outline crosses, its fronts (sides across the section) and runs (sides on the tet's
// faces), and the apex the tet is coned from so that its crack is the fan from the apex over the
// runs.
#include "cutting/cut_partial.h"

#include <limits>

#include "cutting/cut_coplanar.h"

namespace serosa::cutting::detail {
namespace {

// A corner of S.
struct SPoint {
  V2 p2;  ///< plane coordinates, m
  Combo combo;
  bool boundary = true;  ///< on the section's boundary (else a blade corner inside it)
  OpenKey key;
  bool strict = false;  ///< a section corner strictly inside the blade (may open)
};

const V2& p2_of(const SPoint& p) { return p.p2; }

// Face points of the section's side (u, w) in tet face `key`, computed once per face from the
// face's own data (so both tets sharing it agree), ordered from the smaller label.
FaceEntry& face_points(CutState& cs, const FaceKey& key, const SecVert& u, const SecVert& w) {
  auto [it, fresh] = cs.faces.try_emplace(key);
  if (fresh && !(u.inside && w.inside)) {
    const SecVert& a = u.label < w.label ? u : w;
    const SecVert& b = u.label < w.label ? w : u;
    for (double s : outline_crossings(cs, a.p2, b.p2)) {
      FacePoint fp;
      fp.s = s;
      fp.combo.add(a.combo, 1.0 - s);
      fp.combo.add(b.combo, s);
      it->second.points.push_back(fp);
    }
  }
  return it->second;
}

// Barycentric combination of tet t's nodes giving point p (current positions).
Combo barycentric(const CutState& cs, const Tet& t, const Vec3& p) {
  const Vec3 &a = cs.mesh.x[t[0]], &b = cs.mesh.x[t[1]], &c = cs.mesh.x[t[2]], &d = cs.mesh.x[t[3]];
  const double v = signed_volume(a, b, c, d);
  std::array<double, 4> w{signed_volume(p, b, c, d) / v, signed_volume(a, p, c, d) / v,
                          signed_volume(a, b, p, d) / v, 0.0};
  w[3] = 1.0 - w[0] - w[1] - w[2];
  Combo out;
  for (int k = 0; k < 4; ++k) out.add(t[k], w[static_cast<std::size_t>(k)]);
  return out;
}

// The corners of S on the section's side (u, w): u itself when it lies inside the blade, then
// the outline's crossings of the side (face points, or the crossings of a coplanar edge, found
// by classify). Sets info.interacts when it adds one, info.pinned when u and w share no face.
void add_side_corners(CutState& cs, const SecVert& u, const SecVert& w, TetInfo& info,
                      std::vector<SPoint>& sp, bool& any_strict) {
  if (u.inside) {
    any_strict = any_strict || u.strict;
    OpenKey open;
    if (u.support[1] < 0)
      open.node = u.support[0];
    else
      open.edge = u.label;
    sp.push_back({u.p2, u.combo, true, open, u.strict});
    info.interacts = true;
  }
  const FaceKey key = face_key_of(u, w);
  if (key[0] == -2) {
    info.pinned = true;  // unordered section (a sliver): no opening here
    return;
  }
  if (key[0] == -1) {  // along a coplanar edge: the outline's crossings of it (classify)
    const SecVert& lo = u.support[0] < w.support[0] ? u : w;
    const SecVert& hi = u.support[0] < w.support[0] ? w : u;
    const std::int32_t na = u.support[0], nb = w.support[0];
    if (cs.nodes[na].inside && cs.nodes[nb].inside) return;  // no crossing (classify)
    for (const CopPoint& cp : cop_edge(cs, na, nb)) {
      sp.push_back({lo.p2 + cp.s * (hi.p2 - lo.p2), cp.combo, true, {}, false});
      info.interacts = true;
    }
    return;
  }
  const FaceEntry& fe = face_points(cs, key, u, w);
  const SecVert& a = u.label < w.label ? u : w;
  const SecVert& b = u.label < w.label ? w : u;
  for (const FacePoint& fp : fe.points) {
    sp.push_back({a.p2 + fp.s * (b.p2 - a.p2), fp.combo, true, {}, false});
    info.interacts = true;
  }
}

// The blade's corners inside the section (sv, counter-clockwise) by more than tol: corners of S
// off the section's boundary.
void add_blade_corners(const CutState& cs, const Tet& t, const std::vector<SecVert>& sv,
                       std::vector<SPoint>& sp) {
  const std::size_t ns = sv.size();
  for (std::size_t k = 0; k < cs.blade2.size(); ++k) {
    double margin = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < ns; ++i) {
      const V2 e = sv[(i + 1) % ns].p2 - sv[i].p2;
      const V2 q = cs.blade2[k] - sv[i].p2;
      margin = std::min(margin, (e.x() * q.y() - e.y() * q.x()) / e.norm());
    }
    if (margin > cs.tol)
      sp.push_back({cs.blade2[k], barycentric(cs, t, cs.blade.points()[k]), false, {}, false});
  }
}

// Largest distance between two section vertices, m.
double diameter(const std::vector<SecVert>& sv) {
  double diam = 0.0;
  for (std::size_t i = 0; i < sv.size(); ++i)
    for (std::size_t j = i + 1; j < sv.size(); ++j)
      diam = std::max(diam, (sv[i].p2 - sv[j].p2).norm());
  return diam;
}

// S's centre (the mean of its corners sp, which lies strictly inside S when S has area) if it
// lies inside the blade by more than tol: a pinned tet is coned from it by the second pass.
void find_centre(const CutState& cs, const std::vector<SPoint>& sp, double diam, TetInfo& info) {
  info.has_centre = false;
  if (sp.size() < 3) return;
  std::vector<V2> ring;
  for (const SPoint& p : sp) ring.push_back(p.p2);
  auto id = [](const V2& p) -> const V2& { return p; };
  const V2 c = sort_ccw(ring, id);
  if (!(fan_area_from(c, ring, id) > cs.tol * diam)) return;
  Combo centre;
  for (const SPoint& p : sp) centre.add(p.combo, 1.0 / static_cast<double>(sp.size()));
  if (!(cs.blade.inside_margin(centre.cur(cs.mesh)) > cs.tol)) return;
  info.centre = centre;
  info.has_centre = true;
}

// q lies on the boundary of the section sv (within 1e-9 of its diameter).
bool on_section_boundary(const std::vector<SecVert>& sv, double diam, const V2& q) {
  const std::size_t ns = sv.size();
  for (std::size_t i = 0; i < ns; ++i) {
    const V2 e = sv[(i + 1) % ns].p2 - sv[i].p2;
    const double l2 = e.squaredNorm();
    const double s = std::clamp(e.dot(q - sv[i].p2) / l2, 0.0, 1.0);
    if ((sv[i].p2 + s * e - q).norm() <= 1e-9 * diam) return true;
  }
  return false;
}

// Per side k of S (sp[k], sp[k + 1], counter-clockwise): 1 when it runs across the section (a
// front), 0 when it lies on the section's boundary (a run).
std::vector<char> mark_fronts(const std::vector<SPoint>& sp, const std::vector<SecVert>& sv,
                              double diam) {
  const std::size_t n = sp.size();
  std::vector<char> front(n, 0);
  for (std::size_t k = 0; k < n; ++k) {
    const SPoint &p = sp[k], &q = sp[(k + 1) % n];
    front[k] = !(p.boundary && q.boundary && on_section_boundary(sv, diam, 0.5 * (p.p2 + q.p2)));
  }
  return front;
}

// The fan from q over S's runs with an end that may open (strictly inside): the crack, at most.
double fan_area(const std::vector<SPoint>& sp, const std::vector<char>& front, const V2& q) {
  const std::size_t n = sp.size();
  double a = 0.0;
  for (std::size_t k = 0; k < n; ++k)
    if (!front[k] && (sp[k].strict || sp[(k + 1) % n].strict))
      a += area2d(q, sp[k].p2, sp[(k + 1) % n].p2);
  return a;
}

// The apex that touches every front side, when one does: the midpoint of S's only front side,
// or the blade's corner where its two front sides meet. Leaves info.apex empty otherwise.
void apex_on_every_front(const std::vector<SPoint>& sp, const std::vector<char>& front,
                         TetInfo& info) {
  const std::size_t n = sp.size();
  std::size_t fronts = 0;
  for (std::size_t k = 0; k < n; ++k) fronts += front[k] ? 1 : 0;
  // One chain of front sides: its start is a front side after a run.
  std::size_t chains = 0, first = 0;
  for (std::size_t k = 0; k < n; ++k)
    if (front[k] && !front[(k + n - 1) % n]) {
      ++chains;
      first = k;
    }
  info.apex = Combo{};
  if (chains == 1 && fronts == 1) {
    info.apex.add(sp[first].combo, 0.5);
    info.apex.add(sp[(first + 1) % n].combo, 0.5);
    info.apex2 = 0.5 * (sp[first].p2 + sp[(first + 1) % n].p2);
  } else if (chains == 1 && fronts == 2 && !sp[(first + 1) % n].boundary) {
    info.apex = sp[(first + 1) % n].combo;
    info.apex2 = sp[(first + 1) % n].p2;
  }
}

// The midpoint of a front side or blade corner inside the section whose fan covers most of S.
void widest_fan_apex(const std::vector<SPoint>& sp, const std::vector<char>& front, TetInfo& info) {
  const std::size_t n = sp.size();
  double best = -1.0;
  for (std::size_t k = 0; k < n; ++k) {
    if (front[k]) {
      const V2 mid = 0.5 * (sp[k].p2 + sp[(k + 1) % n].p2);
      const double a = fan_area(sp, front, mid);
      if (a > best) {
        best = a;
        info.apex = Combo{};
        info.apex.add(sp[k].combo, 0.5);
        info.apex.add(sp[(k + 1) % n].combo, 0.5);
        info.apex2 = mid;
      }
    }
    if (!sp[k].boundary) {
      const double a = fan_area(sp, front, sp[k].p2);
      if (a > best) {
        best = a;
        info.apex = sp[k].combo;
        info.apex2 = sp[k].p2;
      }
    }
  }
}

// The apex of a partial tet whose S (sp, counter-clockwise, with area `area`) has area.
void choose_apex(const CutState& cs, const std::vector<SPoint>& sp, const std::vector<char>& front,
                 double area, TetInfo& info) {
  apex_on_every_front(sp, front, info);
  if (info.apex.count > 0 &&
      (!cs.options.reopen_pinned || fan_area(sp, front, info.apex2) >= (1.0 - 1e-9) * area))
    return;
  // No point touches every front side (two runs, more than two front sides, or two front
  // sides meeting on the section's boundary). The second pass, when on, cones such a tet
  // from S's centre and cuts it again; otherwise the crack here is the fan from the apex
  // that covers most of S: the midpoint of a front side or a blade corner inside the
  // section. The fan lies in S (S is convex), so the crack stays on the blade; it misses the
  // part of S beyond the front sides away from the apex (counted in tets_short).
  if (cs.options.reopen_pinned && info.has_centre) {
    info.pinned = true;
    info.runs.clear();
    return;
  }
  if (info.apex.count > 0) return;
  widest_fan_apex(sp, front, info);
}

}  // namespace

std::vector<SecVert> section(const CutState& cs, const Tet& t, const TetInfo& info) {
  std::vector<SecVert> sv;
  for (int i = 0; i < 4; ++i) {
    if (info.sign[i] == Sign::kZero) {
      SecVert v;
      v.label = edge_key(t[i], t[i]);
      v.support = {t[i], -1};
      v.combo.add(t[i], 1.0);
      v.inside = cs.nodes.at(t[i]).inside;
      v.strict = cs.nodes.at(t[i]).strict;
      sv.push_back(v);
    }
    for (int j = i + 1; j < 4; ++j) {
      if (!crossing_edge(info, i, j)) continue;
      const EdgeInfo& e = cs.edges.at(edge_key(t[i], t[j]));
      SecVert v;
      v.label = edge_key(t[i], t[j]);
      v.support = {t[i], t[j]};
      v.combo = edge_combo(t[i], t[j], e.t);
      v.inside = e.inside;
      v.strict = e.strict;
      sv.push_back(v);
    }
  }
  for (SecVert& v : sv) v.p2 = cs.blade.to_plane(v.combo.cur(cs.mesh));
  sort_ccw(sv, [](const SecVert& v) -> const V2& { return v.p2; });
  return sv;
}

FaceKey face_key_of(const SecVert& u, const SecVert& w) {
  std::array<std::int32_t, 4> ids{u.support[0], u.support[1], w.support[0], w.support[1]};
  std::sort(ids.begin(), ids.end());
  FaceKey key{-1, -1, -1};
  int n = 0;
  for (std::int32_t v : ids)
    if (v >= 0 && (n == 0 || key[static_cast<std::size_t>(n - 1)] != v)) {
      if (n == 3) return {-2, -2, -2};
      key[static_cast<std::size_t>(n++)] = v;
    }
  if (n < 3) return {-1, -1, -1};
  return key;
}

std::int32_t face_point_id(CutState& cs, FacePoint& fp) {
  if (fp.id < 0) {
    fp.id = cs.weld.add_point(fp.combo.parent());
    ++cs.result.stats.face_points;
  }
  return fp.id;
}

void analyse_partial(CutState& cs, const Tet& t, TetInfo& info) {
  const std::vector<SecVert> sv = section(cs, t, info);
  const double diam = diameter(sv);
  std::vector<SPoint> sp;   // S's corners
  bool any_strict = false;  // a corner of S that may open
  for (std::size_t i = 0; i < sv.size(); ++i)
    add_side_corners(cs, sv[i], sv[(i + 1) % sv.size()], info, sp, any_strict);
  add_blade_corners(cs, t, sv, sp);
  if (cs.options.reopen_pinned) find_centre(cs, sp, diam, info);
  if (info.pinned || !info.interacts) return;
  const V2 c = sort_ccw(sp, p2_of);
  const double area = fan_area_from(c, sp, p2_of);
  if (sp.size() < 3 || !(area > cs.tol * diam)) {
    // S has no area: nothing opens here; split welded like a pinned tet. When no corner of
    // S is strictly inside the blade, no edge or node of the tet could open anyway: the blade
    // only grazes it (a point or a segment of its section on the blade's outline).
    info.pinned = true;
    info.grazed = !any_strict;
    return;
  }
  // S's sides on the section's boundary ("runs") or across it (the front).
  const std::vector<char> front = mark_fronts(sp, sv, diam);
  const std::size_t n = sp.size();
  info.s_area = area;
  for (std::size_t k = 0; k < n; ++k)
    if (!front[k])
      info.runs.push_back({sp[k].p2, sp[(k + 1) % n].p2, sp[k].key, sp[(k + 1) % n].key});
  choose_apex(cs, sp, front, area, info);
}

bool crack_short(const CutState& cs, const TetInfo& info) {
  auto opens = [&](const OpenKey& k) {
    if (k.node >= 0) return cs.weld.find_clone(k.node).has_value();
    if (k.edge == 0) return false;
    const auto it = cs.edges.find(k.edge);
    return it != cs.edges.end() && it->second.open;
  };
  double opened = 0.0;
  for (const RunSide& r : info.runs)
    if (opens(r.ka) || opens(r.kb)) opened += area2d(info.apex2, r.a, r.b);
  return !(opened >= (1.0 - 1e-9) * info.s_area);
}

}  // namespace serosa::cutting::detail

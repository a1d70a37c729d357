#include "cutting/validate.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <set>
#include <sstream>

#include "engine/boundary.h"
#include "engine/geometry/point_triangle.h"
#include "engine/mesh_check.h"
#include "engine/node_components.h"

namespace serosa::cutting {
namespace {

Tri sorted(Tri t) {
  std::sort(t.begin(), t.end());
  return t;
}

std::string str(double v) {
  std::ostringstream s;
  s.precision(17);
  s << v;
  return s.str();
}

// Structure (engine's checker: finite rest coordinates, positive volumes, faces shared by at most
// two tets, consistent orientation), finite current positions and velocities, no new unused nodes.
// Returns the checks of before and after.
std::pair<MeshCheckReport, MeshCheckReport> check_structure(const TetMesh& before,
                                                            const TetMesh& after,
                                                            const CutCheckOptions& options,
                                                            CutCheckReport& rep) {
  auto problem = [&](std::string s) { rep.problems.push_back(std::move(s)); };
  const MeshCheckReport mc = check_mesh(after);
  for (std::int32_t i = 0; i < after.num_nodes(); ++i) {
    const bool xf = i < static_cast<std::int32_t>(after.x.size()) && after.x[i].allFinite();
    const bool vf = i >= static_cast<std::int32_t>(after.v.size()) || after.v[i].allFinite();
    if (!xf || !vf) {
      problem("node " + std::to_string(i) + " has a non-finite current position or velocity");
      break;
    }
  }
  for (const std::string& p : mc.problems) problem("check_mesh: " + p);
  rep.min_quality = mc.min_quality;
  const MeshCheckReport mb = check_mesh(before);
  if (!options.unused_nodes_ok && mc.unreferenced_nodes > mb.unreferenced_nodes) {
    problem("the cut left " + std::to_string(mc.unreferenced_nodes - mb.unreferenced_nodes) +
            " new unreferenced nodes");
  }

  return {mb, mc};
}

// Volume, total and per group.
void check_volume(const MeshCheckReport& mb, const MeshCheckReport& mc,
                  const CutCheckOptions& options, CutCheckReport& rep) {
  auto problem = [&](std::string s) { rep.problems.push_back(std::move(s)); };
  rep.volume_before_m3 = mb.volume_m3;
  rep.volume_after_m3 = mc.volume_m3;
  const double scale = std::abs(mb.volume_m3);
  if (std::abs(mc.volume_m3 - mb.volume_m3) > options.volume_rel * scale)
    problem("total volume changed from " + str(mb.volume_m3) + " to " + str(mc.volume_m3));
  for (const auto& [g, v] : mb.group_volume_m3) {
    const auto it = mc.group_volume_m3.find(g);
    const double va = it == mc.group_volume_m3.end() ? 0.0 : it->second;
    if (std::abs(va - v) > options.volume_rel * std::abs(v))  // relative to the group's own
      problem("group " + std::to_string(g) + " volume changed from " + str(v) + " to " + str(va));
  }
  for (const auto& [g, v] : mc.group_volume_m3)
    if (!mb.group_volume_m3.contains(g)) problem("new group " + std::to_string(g));
}

// Boundary faces: kept, on the old surface, or on the blade.
void check_boundary(const TetMesh& before, const TetMesh& after, const ConvexPolygon& blade,
                    const CutCheckOptions& options, CutCheckReport& rep) {
  auto problem = [&](std::string s) { rep.problems.push_back(std::move(s)); };
  const FaceCensus fb = face_census(before);
  const FaceCensus fa = face_census(after);
  std::set<Tri> old_faces;
  for (const BoundaryFace& f : fb.boundary) old_faces.insert(sorted(f.nodes));
  const double tol = options.geometry_tol_m;
  for (const BoundaryFace& f : fa.boundary) {
    if (old_faces.contains(sorted(f.nodes))) {
      ++rep.boundary_faces_kept;
      continue;
    }
    const Vec3& a = after.x[f.nodes[0]];
    const Vec3& b = after.x[f.nodes[1]];
    const Vec3& c = after.x[f.nodes[2]];
    const Vec3 centroid = (a + b + c) / 3.0;
    bool on_blade = true;
    for (const Vec3* p : {&a, &b, &c, &centroid})
      on_blade = on_blade && std::abs(blade.signed_distance(*p)) <= tol &&
                 blade.contains_projection(*p, tol);
    if (on_blade) {
      ++rep.boundary_faces_on_blade;
      rep.blade_face_area_m2 += 0.5 * (b - a).cross(c - a).norm();
      continue;
    }
    bool on_old = false;
    for (const BoundaryFace& o : fb.boundary) {
      const Vec3& oa = before.x[o.nodes[0]];
      const Vec3& ob = before.x[o.nodes[1]];
      const Vec3& oc = before.x[o.nodes[2]];
      bool all = true;
      for (const Vec3* p : {&a, &b, &c, &centroid})
        all = all && geometry::point_triangle_distance(*p, oa, ob, oc) <= tol;
      if (all) {
        on_old = true;
        break;
      }
    }
    if (on_old) {
      ++rep.boundary_faces_on_old;
      continue;
    }
    problem("boundary face (" + std::to_string(f.nodes[0]) + ", " + std::to_string(f.nodes[1]) +
            ", " + std::to_string(f.nodes[2]) + ") lies neither on the old surface nor on the " +
            "blade (plane distance of centroid " + str(blade.signed_distance(centroid)) +
            " m, inside margin " + str(blade.inside_margin(centroid)) + " m)");
    if (rep.problems.size() > 20) break;
  }
}

// No tet crosses the polygon.
void check_no_crossing(const TetMesh& after, const ConvexPolygon& blade, double tol,
                       CutCheckReport& rep) {
  auto problem = [&](std::string s) { rep.problems.push_back(std::move(s)); };
  for (std::int32_t ti = 0; ti < after.num_tets(); ++ti) {
    const Tet& t = after.tets[ti];
    bool crosses = false;
    for (int i = 0; i < 4 && !crosses; ++i)
      for (int j = i + 1; j < 4 && !crosses; ++j) {
        const double pi = blade.signed_distance(after.x[t[i]]);
        const double pj = blade.signed_distance(after.x[t[j]]);
        if ((pi > tol && pj < -tol) || (pi < -tol && pj > tol)) {
          const Vec3 p = after.x[t[i]] + pi / (pi - pj) * (after.x[t[j]] - after.x[t[i]]);
          crosses = blade.contains_projection(p, -tol);
        }
      }
    if (crosses) {
      problem("tet " + std::to_string(ti) + " crosses the blade polygon");
      break;
    }
  }
}

// Every piece on one side; the positive pieces hold exactly the clipped volume.
void check_pieces(const TetMesh& before, const TetMesh& after, const ConvexPolygon& blade,
                  const CutCheckOptions& options, double scale, CutCheckReport& rep) {
  auto problem = [&](std::string s) { rep.problems.push_back(std::move(s)); };
  const double tol = options.geometry_tol_m;
  const std::vector<std::int32_t> comp = tet_components(after);
  const std::int32_t nc = comp.empty() ? 0 : *std::max_element(comp.begin(), comp.end()) + 1;
  rep.components = nc;
  std::vector<char> has_pos(static_cast<std::size_t>(nc), 0), has_neg(has_pos);
  std::vector<double> vol(static_cast<std::size_t>(nc), 0.0);
  for (std::int32_t ti = 0; ti < after.num_tets(); ++ti) {
    const auto c = static_cast<std::size_t>(comp[static_cast<std::size_t>(ti)]);
    vol[c] += after.rest_volume(ti);
    for (std::int32_t id : after.tets[ti]) {
      const double phi = blade.signed_distance(after.x[id]);
      has_pos[c] = has_pos[c] || phi > tol;
      has_neg[c] = has_neg[c] || phi < -tol;
    }
  }
  double pos_vol = 0.0;
  for (std::size_t c = 0; c < vol.size(); ++c) {
    if (has_pos[c] && has_neg[c]) {
      problem("piece " + std::to_string(c) + " (of " + std::to_string(nc) +
              ") has nodes on both sides of the blade's plane");
      break;
    }
    if (has_pos[c]) pos_vol += vol[c];
  }
  rep.positive_volume_m3 = pos_vol;
  rep.clipped_volume_m3 =
      clipped_positive_volume(before, blade.normal(), blade.offset(), options.plane_tol_m);
  if (std::abs(pos_vol - rep.clipped_volume_m3) > options.volume_rel * scale)
    problem("the positive pieces hold " + str(pos_vol) + " m^3, the exact clipped volume is " +
            str(rep.clipped_volume_m3) + " m^3");
}

}  // namespace

CutCheckReport check_cut(const TetMesh& before, const TetMesh& after, const ConvexPolygon& blade,
                         const CutCheckOptions& options) {
  CutCheckReport rep;
  const auto [mb, mc] = check_structure(before, after, options, rep);
  check_volume(mb, mc, options, rep);
  check_boundary(before, after, blade, options, rep);
  if (options.expect_separated) {
    check_no_crossing(after, blade, options.geometry_tol_m, rep);
    check_pieces(before, after, blade, options, std::abs(mb.volume_m3), rep);
  }
  rep.ok = rep.problems.empty();
  return rep;
}

std::vector<std::int32_t> tet_components(const TetMesh& mesh) {
  const std::vector<std::int32_t> node = node_components(mesh);
  std::vector<std::int32_t> out;
  out.reserve(mesh.tets.size());
  for (const Tet& t : mesh.tets) out.push_back(node[static_cast<std::size_t>(t[0])]);
  return out;
}

double clipped_positive_volume(const TetMesh& mesh, const Vec3& normal, double offset,
                               double plane_tol_m) {
  double total = 0.0;
  auto vol = [](const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    return std::abs(signed_volume(a, b, c, d));
  };
  for (const Tet& t : mesh.tets) {
    std::array<double, 4> phi{};
    for (int k = 0; k < 4; ++k) {
      phi[k] = normal.dot(mesh.x[t[k]]) - offset;
      if (std::abs(phi[k]) <= plane_tol_m) phi[k] = 0.0;
    }
    // Nodes strictly positive / non-positive; a zero node counts with the negative side (it adds
    // no volume to the positive part).
    std::array<int, 4> pos{}, neg{};
    int np = 0, nn = 0;
    for (int k = 0; k < 4; ++k) (phi[k] > 0.0 ? pos[np++] : neg[nn++]) = k;
    const Vec3 &r0 = mesh.rest[t[0]], &r1 = mesh.rest[t[1]], &r2 = mesh.rest[t[2]],
               &r3 = mesh.rest[t[3]];
    const double whole = vol(r0, r1, r2, r3);
    if (np == 0) continue;
    if (nn == 0) {
      total += whole;
      continue;
    }
    // Cut point on the edge from positive node i to non-positive node j (rest positions).
    auto cut = [&](int i, int j) {
      const double ti = phi[i] / (phi[i] - phi[j]);
      return Vec3(mesh.rest[t[i]] + ti * (mesh.rest[t[j]] - mesh.rest[t[i]]));
    };
    if (np == 1) {
      total +=
          vol(mesh.rest[t[pos[0]]], cut(pos[0], neg[0]), cut(pos[0], neg[1]), cut(pos[0], neg[2]));
    } else if (np == 3) {
      total += whole - vol(mesh.rest[t[neg[0]]], cut(pos[0], neg[0]), cut(pos[1], neg[0]),
                           cut(pos[2], neg[0]));
    } else {  // a prism (a, b, ac, ad, bc, bd) in three tets
      const Vec3& a = mesh.rest[t[pos[0]]];
      const Vec3& b = mesh.rest[t[pos[1]]];
      const Vec3 ac = cut(pos[0], neg[0]), ad = cut(pos[0], neg[1]), bc = cut(pos[1], neg[0]),
                 bd = cut(pos[1], neg[1]);
      total += vol(a, b, ac, ad) + vol(b, ac, ad, bd) + vol(b, ac, bd, bc);
    }
  }
  return total;
}

namespace {

// Components of the tets `keep` accepts (by index), connected through shared nodes.
template <typename Keep>
std::int32_t count_components_of(const TetMesh& mesh, Keep keep) {
  std::vector<std::int32_t> parent(static_cast<std::size_t>(mesh.num_nodes()));
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](std::int32_t a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  };
  std::vector<char> used(parent.size(), 0);
  for (std::size_t i = 0; i < mesh.tets.size(); ++i) {
    if (!keep(i)) continue;
    const Tet& t = mesh.tets[i];
    for (int k = 0; k < 4; ++k) {
      used[t[k]] = 1;
      parent[find(t[k])] = find(t[0]);
    }
  }
  std::int32_t count = 0;
  for (std::int32_t i = 0; i < mesh.num_nodes(); ++i) count += used[i] && find(i) == i ? 1 : 0;
  return count;
}

}  // namespace

std::int32_t count_components(const TetMesh& mesh) {
  return count_components_of(mesh, [](std::size_t) { return true; });
}

std::int32_t count_components(const TetMesh& mesh, std::uint16_t group) {
  return count_components_of(mesh, [&](std::size_t t) { return mesh.group[t] == group; });
}

}  // namespace serosa::cutting

// Helpers shared by the cutting tests: blade polygons and cut-then-check.
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "cutting/convex_polygon.h"
#include "cutting/cut_mesh.h"
#include "cutting/validate.h"
#include "engine/topology_delta.h"

namespace serosa::cutting::testing {

/// A square of half-size s centred at c in the plane with normal n, turned by angle rot (rad).
inline ConvexPolygon square(const Vec3& n, const Vec3& c, double s, double rot = 0.0) {
  const Vec3 nn = n.normalized();
  const Vec3 a = std::abs(nn.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  Vec3 u = (a - nn * nn.dot(a)).normalized();
  Vec3 v = nn.cross(u);
  const Vec3 u2 = std::cos(rot) * u + std::sin(rot) * v;
  v = nn.cross(u2);
  u = u2;
  return ConvexPolygon(
      {c - s * u - s * v, c + s * u - s * v, c + s * u + s * v, c - s * u + s * v});
}

struct Applied {
  TetMesh after;
  CutResult result;
  CutCheckReport report;
};

/// Cuts `mesh` by `blade`, applies the delta and runs the invariant checker.
inline Applied cut_and_check(const TetMesh& mesh, const ConvexPolygon& blade,
                             bool expect_separated = false, const CutOptions& options = {}) {
  Applied a{mesh, cut_mesh(mesh, blade, options), {}};
  apply(a.after, a.result.delta);
  CutCheckOptions co;
  co.geometry_tol_m = 4.0 * a.result.stats.tolerance_m + 1e-12;
  co.expect_separated = expect_separated;
  co.plane_tol_m = a.result.stats.tolerance_m;
  a.report = check_cut(mesh, a.after, blade, co);
  return a;
}

inline std::string problems(const CutCheckReport& r) {
  std::string s;
  for (const std::string& p : r.problems) s += p + "\n";
  return s;
}

}  // namespace serosa::cutting::testing

#include "cutting/scissors_stroke.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "cutting/tet_bvh.h"
#include "engine/geometry/tet_barycentric.h"
#include "engine/tool_geometry.h"

namespace serosa::cutting {
namespace {

static_assert(sizeof(StrokeSample) == 64, "written as plain bytes: no padding");

Eigen::Quaterniond quat(const ToolState& t) {
  Eigen::Quaterniond q(t.quat_wxyz[0], t.quat_wxyz[1], t.quat_wxyz[2], t.quat_wxyz[3]);
  if (!(q.norm() > 0.0)) return Eigen::Quaterniond::Identity();
  return q.normalized();
}

// The blade's final edge direction and the shaft's side, in the plane's coordinates.
struct EndAxes {
  Vec2 hinge, side, blade[2];
};

EndAxes end_axes(const PlaneFit& fit, const ToolState& end, const Vec2& hinge) {
  const ToolFrame f = tool_frame(end);
  const auto dir = [&](const Vec3& w) { return Vec2(fit.u.dot(w), fit.v.dot(w)); };
  EndAxes a{hinge, dir(f.side), {}};
  const double h = 0.5 * std::max(end.jaw_rad, 0.0);
  for (int k = 0; k < 2; ++k) {
    const double s = k == 0 ? 1.0 : -1.0;
    a.blade[k] = dir(std::cos(h) * f.forward + s * std::sin(h) * f.side);
  }
  return a;
}

// Blade k's share of the stroke: its samples and the hinge's, beyond its final edge, on its side
// of the shaft.
std::vector<Vec2> blade_outline(const std::vector<Vec2>& q, const std::vector<StrokeSample>& s,
                                int k, const EndAxes& ax) {
  std::vector<Vec2> mine;
  for (std::size_t i = 0; i < q.size(); ++i)
    if (s[i].blade == k || s[i].blade < 0) mine.push_back(q[i]);
  std::vector<Vec2> outline;
  for (std::size_t i : hull2d(mine)) outline.push_back(mine[i]);
  const double sign = k == 0 ? 1.0 : -1.0;
  outline = clip_halfplane(outline, ax.hinge, sign * ax.side);
  const Vec2 d = ax.blade[k].normalized();
  const Vec2 away = sign * (ax.side - ax.side.dot(d) * d);
  if (away.norm() > 0.0) outline = clip_halfplane(outline, ax.hinge, away);
  return outline;
}

// The outline without corners closer than a millionth of its size to the previous one, nor
// corners where it barely turns (rounding would call them repeated or concave).
std::vector<Vec2> clean(const std::vector<Vec2>& outline) {
  double size = 0.0;
  for (const Vec2& q : outline) size = std::max(size, (q - outline.front()).norm());
  const double near = 1e-6 * size;
  std::vector<Vec2> out;
  for (const Vec2& q : outline)
    if (out.empty() || (q - out.back()).norm() > near) out.push_back(q);
  while (out.size() > 1 && (out.back() - out.front()).norm() <= near) out.pop_back();
  for (bool changed = true; changed && out.size() > 3;) {
    changed = false;
    for (std::size_t i = 0; i < out.size() && out.size() > 3; ++i) {
      const Vec2& a = out[(i + out.size() - 1) % out.size()];
      const Vec2& b = out[i];
      const Vec2& c = out[(i + 1) % out.size()];
      const Vec2 ab = b - a, bc = c - b;
      if (ab.x() * bc.y() - ab.y() * bc.x() <= 1e-9 * ab.norm() * bc.norm()) {
        out.erase(out.begin() + static_cast<std::ptrdiff_t>(i));
        changed = true;
      }
    }
  }
  return out;
}

std::optional<ConvexPolygon> to_polygon(const PlaneFit& fit, const std::vector<Vec2>& raw) {
  const std::vector<Vec2> outline = clean(raw);
  if (outline.size() < 3) return std::nullopt;
  std::vector<Vec3> w;
  for (const Vec2& q : outline) w.push_back(fit.to_world(q));
  return ConvexPolygon::make(std::move(w), 1e-6);
}

// The carried samples and, for each sampled pose (a hinge followed by its two tips), points
// along both blade edges between them: the blade is straight, so they lie on the swept surface.
std::vector<Vec3> surface_points(const std::vector<StrokeSample>& s, const std::vector<Vec3>& p) {
  std::vector<Vec3> out = p;
  for (std::size_t i = 0; i + 2 < s.size(); ++i) {
    if (s[i].blade >= 0 || s[i + 1].blade != 0 || s[i + 2].blade != 1) continue;
    for (std::size_t k = 1; k <= 2; ++k)
      for (int j = 1; j <= kBladeEdgePoints; ++j) {
        const double f = static_cast<double>(j) / (kBladeEdgePoints + 1);
        out.push_back((1.0 - f) * p[i] + f * p[i + k]);
      }
  }
  return out;
}

// The swept surface of a bent stroke over its plane; std::nullopt for a stroke near its plane.
std::optional<StrokeSurface> bent_surface(const PlaneFit& fit, const std::vector<Vec3>& points) {
  if (!(fit.deviation_m > kBentStrokeTol)) return std::nullopt;
  double size = 0.0;
  for (const Vec3& x : points) size = std::max(size, (x - points.front()).norm());
  return StrokeSurface::make(fit, points, 1e-3 * size);
}

}  // namespace

ToolState interpolate(const ToolState& a, const ToolState& b, double s) {
  ToolState t = b;
  for (int i = 0; i < 3; ++i) t.tip_m[i] = a.tip_m[i] + s * (b.tip_m[i] - a.tip_m[i]);
  t.jaw_rad = a.jaw_rad + s * (b.jaw_rad - a.jaw_rad);
  t.time_s = a.time_s + s * (b.time_s - a.time_s);
  const Eigen::Quaterniond q = quat(a).slerp(s, quat(b));
  t.quat_wxyz = {q.w(), q.x(), q.y(), q.z()};
  return t;
}

ScissorsStroke::ScissorsStroke(const ToolState& start, std::uint64_t topology_version) {
  m_rec.start = start;
  m_rec.topology_version = topology_version;
}

void ScissorsStroke::add(const Vec3& x, std::int32_t blade, const TetMesh& mesh,
                         const TetBvh& bvh) {
  StrokeSample s;
  s.x_m = x;
  s.blade = blade;
  double best = -std::numeric_limits<double>::infinity();
  // The tet that holds x, or the one it is least outside of among the nearest: a blade tip far
  // from the tissue follows the tissue nearest to it (extrapolated, exact for tissue moving
  // rigidly or affinely), so the stroke's outline keeps its shape around the tissue it cut.
  for (double r = kStrokeTrackRadius; r <= 16.0 * kStrokeTrackRadius && s.tet < 0; r *= 2.0) {
    m_candidates.clear();
    if (x.allFinite()) bvh.query(x - Vec3::Constant(r), x + Vec3::Constant(r), m_candidates);
    for (std::int32_t t : m_candidates) {
      const auto w = geometry::tet_barycentric(x, mesh, t);
      if (!w) continue;
      const double inside = *std::min_element(w->begin(), w->end());
      if (inside > best) {
        best = inside;
        s.tet = t;
        s.bary = *w;
      }
    }
  }
  m_rec.samples.push_back(s);
}

void ScissorsStroke::sweep(const ToolState& before, const ToolState& now, const TetMesh& mesh,
                           const TetBvh& bvh) {
  const auto sample = [&](const ToolState& pose) {
    const ToolFrame f = tool_frame(pose);
    add(f.hinge, -1, mesh, bvh);
    add(jaw_tip(f, pose.jaw_rad, 0), 0, mesh, bvh);
    add(jaw_tip(f, pose.jaw_rad, 1), 1, mesh, bvh);
  };
  if (m_rec.samples.empty()) sample(before);
  const double half_angle = 0.5 * std::abs(now.jaw_rad - before.jaw_rad);
  const double turn = quat(before).angularDistance(quat(now));
  const double steps = std::ceil(std::max(half_angle, turn) / kStrokeArcStep);
  const int n = std::isfinite(steps) ? std::clamp(static_cast<int>(steps), 1, 64) : 1;
  for (int j = 1; j <= n; ++j)
    sample(interpolate(before, now, static_cast<double>(j) / static_cast<double>(n)));
  ++m_rec.steps;
}

void ScissorsStroke::add_segment(const Vec3& a, const Vec3& b, const TetMesh& mesh,
                                 const TetBvh& bvh) {
  add(a, -1, mesh, bvh);
  add(0.5 * (a + b), -1, mesh, bvh);
  add(b, -1, mesh, bvh);
}

void ScissorsStroke::carried(const TetMesh& mesh, std::vector<Vec3>& out) const {
  const bool same_tets = mesh.topology_version == m_rec.topology_version;
  out.clear();
  for (const StrokeSample& s : m_rec.samples) {
    if (!same_tets || s.tet < 0 || s.tet >= mesh.num_tets()) {
      out.push_back(s.x_m);
      continue;
    }
    const Tet& tet = mesh.tets[static_cast<std::size_t>(s.tet)];
    Vec3 p = Vec3::Zero();
    for (int i = 0; i < 4; ++i)
      p += s.bary[static_cast<std::size_t>(i)] *
           mesh.x[static_cast<std::size_t>(tet[static_cast<std::size_t>(i)])];
    out.push_back(p);
  }
}

StrokePolygons ScissorsStroke::polygons(const TetMesh& mesh, const ToolState& end,
                                        double closed_rad) const {
  StrokePolygons out;
  std::vector<Vec3> p;
  carried(mesh, p);
  const auto fit = fit_plane(p, tool_frame(m_rec.start).pin);
  if (!fit) return out;
  out.fit = *fit;
  out.surface_points_m = surface_points(m_rec.samples, p);
  out.surface = bent_surface(*fit, out.surface_points_m);
  std::vector<Vec2> q;
  q.reserve(p.size());
  for (const Vec3& x : p) q.push_back(fit->to_plane(x));
  if (end.jaw_rad <= closed_rad) {  // closed: the blades met, one region across both
    std::vector<Vec2> outline;
    for (std::size_t i : hull2d(q)) outline.push_back(q[i]);
    if (auto poly = to_polygon(*fit, outline)) {
      out.polygons.push_back(std::move(*poly));
      out.blades.push_back(0);
    }
    return out;
  }
  Vec2 hinge = fit->to_plane(tool_frame(end).hinge);  // the last hinge sample, carried
  for (std::size_t i = m_rec.samples.size(); i-- > 0;)
    if (m_rec.samples[i].blade < 0) {
      hinge = q[i];
      break;
    }
  const EndAxes ax = end_axes(*fit, end, hinge);
  for (int k = 0; k < 2; ++k)
    if (auto poly = to_polygon(*fit, blade_outline(q, m_rec.samples, k, ax))) {
      out.polygons.push_back(std::move(*poly));
      out.blades.push_back(k);
    }
  return out;
}

}  // namespace serosa::cutting

// The abdomen around the organs (see scenery.h). Geometry is computed in double and stored as
// float; nothing is random, so two runs of a scene draw the same abdomen.
#include "render/scenery.h"

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace serosa::render {
namespace {

using V2 = Eigen::Vector2d;
using V3 = Eigen::Vector3d;

constexpr double kTwoPi = 2.0 * std::numbers::pi;

V3 vec(const std::array<float, 3>& a) { return {a[0], a[1], a[2]}; }

// The plane's frame: `origin` on the plane under the footprint's centre, in-plane axes u (the up
// hint) and v = n x u, so that (u, v, n) is right-handed; `half` is the footprint's half extents
// along u and v, m.
struct PlaneFrame {
  V3 origin = V3::Zero();
  V3 u = V3::UnitX();
  V3 v = V3::UnitY();
  V3 n = V3::UnitZ();
  V2 half = V2::Zero();

  [[nodiscard]] V3 at(const V2& q, double height) const {
    return origin + q.x() * u + q.y() * v + height * n;
  }
  [[nodiscard]] V3 in_plane(const V2& d) const { return d.x() * u + d.y() * v; }
};

// The in-plane axis u: the hint without its normal part, or the world axis least along n.
V3 in_plane_axis(const V3& hint, const V3& n) {
  V3 u = hint - hint.dot(n) * n;
  if (u.norm() > 1e-6 * std::max(hint.norm(), 1e-30)) return u.normalized();
  Eigen::Index axis = 0;
  n.cwiseAbs().minCoeff(&axis);
  const V3 e = V3::Unit(axis);
  return (e - e.dot(n) * n).normalized();
}

PlaneFrame plane_frame(const AbdomenPlacement& p) {
  PlaneFrame f;
  const V3 normal = vec(p.normal);
  f.n = normal.norm() > 1e-12 ? V3(normal.normalized()) : V3::UnitZ();
  f.u = in_plane_axis(vec(p.up_hint), f.n);
  f.v = f.n.cross(f.u);
  // The footprint: the box's eight corners in the plane's (u, v) coordinates.
  const V3 point = vec(p.point_m), lo = vec(p.organs_lo_m), hi = vec(p.organs_hi_m);
  V2 mn = V2::Constant(1e30), mx = V2::Constant(-1e30);
  for (int c = 0; c < 8; ++c) {
    const V3 corner((c & 1) ? hi.x() : lo.x(), (c & 2) ? hi.y() : lo.y(),
                    (c & 4) ? hi.z() : lo.z());
    const V2 q((corner - point).dot(f.u), (corner - point).dot(f.v));
    mn = mn.cwiseMin(q);
    mx = mx.cwiseMax(q);
  }
  const V2 centre = 0.5 * (mn + mx);
  f.origin = point + f.in_plane(centre);
  f.half = (0.5 * (mx - mn)).cwiseMax(V2::Constant(1e-3));
  return f;
}

// In-plane distance of q (plane coordinates) from the footprint rectangle, m; 0 inside.
double footprint_distance(const V2& q, const V2& half) {
  return (q.cwiseAbs() - half).cwiseMax(0.0).norm();
}

double smoothstep(double e0, double e1, double x) {
  const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

// Three crossing waves of 4-9 cm, their sum within [-1, 1].
double undulation(const V2& q) {
  const double x = q.x(), y = q.y();
  const double a = std::sin(kTwoPi * x / 0.071 + 0.3) * std::sin(kTwoPi * y / 0.053 + 1.1);
  const double b = std::sin(kTwoPi * (0.8 * x + 0.6 * y) / 0.043 + 2.0);
  const double c = std::sin(kTwoPi * (-0.35 * x + 0.94 * y) / 0.089 + 0.7);
  return 0.5 * a + 0.3 * b + 0.2 * c;
}

// The wall's height above the plane, m: the undulation, lowered by its amplitude within the
// footprint plus the clearance (so it can only dip there), rising back over the next 3 cm; and
// beyond the flat part the rim, rising quadratically (smoothly: no crease where it starts).
double wall_height(const V2& q, const PlaneFrame& f, const AbdomenDimensions& d) {
  const double clear = d.wall_clearance_m;
  const double lowered = 1.0 - smoothstep(clear, clear + 0.03, footprint_distance(q, f.half));
  const double beyond = std::max(q.norm() - d.wall_flat_radius_m, 0.0);
  return d.wall_amplitude_m * (undulation(q) - lowered) +
         d.wall_rim_curvature_per_m * beyond * beyond;
}

// The wall's unit normal at q, from the height's gradient (central differences).
V3 wall_normal(const V2& q, const PlaneFrame& f, const AbdomenDimensions& d) {
  constexpr double e = 1e-5;
  const double hx = (wall_height(q + V2(e, 0), f, d) - wall_height(q - V2(e, 0), f, d)) / (2 * e);
  const double hy = (wall_height(q + V2(0, e), f, d) - wall_height(q - V2(0, e), f, d)) / (2 * e);
  return (f.n - hx * f.u - hy * f.v).normalized();
}

std::uint32_t add_vertex(Scenery& s, const V3& p, const V3& n) {
  const auto id = static_cast<std::uint32_t>(s.num_vertices());
  for (int k = 0; k < 3; ++k) {
    s.pos.push_back(static_cast<float>(p[k]));
    s.nrm.push_back(static_cast<float>(n[k]));
  }
  return id;
}

// Triangles of a (rows x cols) vertex grid starting at `first`, row-major: the quad (i, j),
// (i+1, j), (i+1, j+1), (i, j+1) is counter-clockwise seen from outside. `wrap`: the last column
// joins the first (a tube's or a lobule's circumference).
void add_grid(Scenery& s, std::uint32_t first, int rows, int cols, bool wrap, SceneryMaterial m) {
  const int quads_across = wrap ? cols : cols - 1;
  const auto id = [&](int i, int j) {
    return first + static_cast<std::uint32_t>(i * cols + (j % cols));
  };
  for (int i = 0; i + 1 < rows; ++i) {
    for (int j = 0; j < quads_across; ++j) {
      s.tri.insert(s.tri.end(), {id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      s.tri.insert(s.tri.end(), {id(i, j), id(i + 1, j + 1), id(i, j + 1)});
      s.material.insert(s.material.end(), {m, m});
    }
  }
}

// The wall: a grid whose cells grow away from the centre (sinh spacing), so the view around the
// organs is finely meshed and the far rim is cheap.
void append_wall(Scenery& s, const PlaneFrame& f, const AbdomenDimensions& d) {
  const int cells = std::max(d.wall_cells, 2);
  constexpr double k = 3.0;
  const auto coord = [&](int i) {
    const double xi = 2.0 * i / cells - 1.0;
    return d.wall_half_width_m * std::sinh(k * xi) / std::sinh(k);
  };
  const auto first = static_cast<std::uint32_t>(s.num_vertices());
  for (int i = 0; i <= cells; ++i) {
    for (int j = 0; j <= cells; ++j) {
      const V2 q(coord(i), coord(j));
      add_vertex(s, f.at(q, wall_height(q, f, d)), wall_normal(q, f, d));
    }
  }
  add_grid(s, first, cells + 1, cells + 1, false, SceneryMaterial::kPeritoneum);
}

// A ring around the footprint: the rounded rectangle at `nominal` m from it, walked
// counter-clockwise by its arc length. ring_point gives, at arc length lambda, the nearest point
// of the footprint and the outward unit direction from it: every point q + s dir (s >= 0) lies
// exactly s from the footprint.
struct Ring {
  V2 half;
  double nominal = 0.0;
  [[nodiscard]] double length() const { return 4.0 * (half.x() + half.y()) + kTwoPi * nominal; }
};

struct RingPoint {
  V2 q;
  V2 dir;
};

RingPoint ring_point(const Ring& r, double lambda) {
  const double ex = r.half.x(), ey = r.half.y();
  const std::array<V2, 4> corner{V2(ex, -ey), V2(ex, ey), V2(-ex, ey), V2(-ex, -ey)};
  const double arc = 0.5 * std::numbers::pi * r.nominal;
  lambda = std::fmod(lambda, r.length());
  if (lambda < 0.0) lambda += r.length();
  for (int k = 0; k < 4; ++k) {
    const V2 a = corner[static_cast<std::size_t>(k)];
    const V2 b = corner[static_cast<std::size_t>((k + 1) % 4)];
    const double side = (b - a).norm();
    const V2 along = (b - a) / std::max(side, 1e-12);
    const V2 out(along.y(), -along.x());
    if (lambda <= side) return {a + lambda * along, out};
    lambda -= side;
    if (lambda <= arc || k == 3) {
      const double phi = std::min(lambda, arc) / std::max(r.nominal, 1e-12);
      return {b, std::cos(phi) * out + std::sin(phi) * along};
    }
    lambda -= arc;
  }
  return {corner[0], V2(1.0, 0.0)};
}

// One bowel loop's centre line: the ring's point pushed out by `offset(lambda)`, one radius above
// the plane.
struct Loop {
  Ring ring;
  double base = 0.0;     // the least distance of the centre line from the footprint, m
  double wiggle = 0.0;   // the meander's reach beyond base, m
  double waves = 1.0;    // meanders per ring
  double phase = 0.0;    // rad
  double radius = 0.01;  // m
  double from = 0.0;     // arc length where the loop starts, m
  double to = 0.0;       // and ends, m
  [[nodiscard]] double offset(double lambda) const {
    return base + wiggle * 0.5 * (1.0 - std::cos(kTwoPi * waves * lambda / ring.length() + phase));
  }
};

V3 centre_line(const Loop& l, const PlaneFrame& f, double lambda) {
  const RingPoint p = ring_point(l.ring, lambda);
  return f.at(p.q + l.offset(lambda) * p.dir, l.radius);
}

// A circle of a tube: centre, radius, its frame (axis t, side = t x the plane's normal), and the
// axial part of its vertices' normals (the rounded ends lean them along t).
struct Section {
  V3 centre;
  V3 t, side;
  double radius = 0.0;
  double lean = 0.0;  // the normals' component along t
};

// The sections of a loop: a hemispherical cap, the body every tube_section_m, the other cap.
std::vector<Section> loop_sections(const Loop& l, const PlaneFrame& f, const AbdomenDimensions& d) {
  const int body = std::max(2, static_cast<int>(std::ceil((l.to - l.from) / d.tube_section_m)));
  const auto section = [&](double lambda) {
    constexpr double e = 1e-4;
    const V3 t = (centre_line(l, f, lambda + e) - centre_line(l, f, lambda - e)).normalized();
    return Section{centre_line(l, f, lambda), t, t.cross(f.n), l.radius, 0.0};
  };
  constexpr int kCap = 5;
  std::vector<Section> out;
  const Section start = section(l.from);
  for (int j = kCap; j >= 1; --j) {  // from the tip towards the body
    const double beta = 0.5 * std::numbers::pi * j / kCap;
    out.push_back({start.centre - l.radius * std::sin(beta) * start.t, start.t, start.side,
                   l.radius * std::cos(beta), -std::sin(beta)});
  }
  for (int i = 0; i <= body; ++i) out.push_back(section(l.from + (l.to - l.from) * i / body));
  const Section end = out.back();
  for (int j = 1; j <= kCap; ++j) {
    const double beta = 0.5 * std::numbers::pi * j / kCap;
    out.push_back({end.centre + l.radius * std::sin(beta) * end.t, end.t, end.side,
                   l.radius * std::cos(beta), std::sin(beta)});
  }
  return out;
}

void append_loop(Scenery& s, const Loop& l, const PlaneFrame& f, const AbdomenDimensions& d) {
  const std::vector<Section> sections = loop_sections(l, f, d);
  const int sides = std::max(d.tube_sides, 3);
  const auto first = static_cast<std::uint32_t>(s.num_vertices());
  for (const Section& c : sections) {
    const double across = std::sqrt(std::max(0.0, 1.0 - c.lean * c.lean));
    for (int j = 0; j < sides; ++j) {
      const double a = kTwoPi * j / sides;
      const V3 radial = std::cos(a) * c.side + std::sin(a) * f.n;
      add_vertex(s, c.centre + c.radius * radial, across * radial + c.lean * c.t);
    }
  }
  add_grid(s, first, static_cast<int>(sections.size()), sides, true, SceneryMaterial::kBowel);
}

// A fat lobule: a flattened ellipsoid (semi-axes a along `t`, b across, c along the normal),
// its centre 0.3 c above the plane (the rest sunk into the wall).
void append_lobule(Scenery& s, const PlaneFrame& f, const V2& q, const V3& t, const V3& abc) {
  constexpr int kRows = 9, kCols = 16;  // latitude rings (poles included), meridians
  const V3 side = f.n.cross(t);         // (t, side, n) right-handed
  const V3 centre = f.at(q, 0.3 * abc.z());
  const auto first = static_cast<std::uint32_t>(s.num_vertices());
  for (int i = 0; i < kRows; ++i) {
    const double theta = std::numbers::pi * i / (kRows - 1);  // 0: top
    for (int j = 0; j < kCols; ++j) {
      const double phi = kTwoPi * j / kCols;
      const V3 unit(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                    std::cos(theta));
      const V3 local = unit.cwiseProduct(abc);
      const V3 grad = unit.cwiseQuotient(abc);
      add_vertex(s, centre + local.x() * t + local.y() * side + local.z() * f.n,
                 (grad.x() * t + grad.y() * side + grad.z() * f.n).normalized());
    }
  }
  add_grid(s, first, kRows, kCols, true, SceneryMaterial::kFat);
}

// The radius of loop j of ring k: spread over [min, max] by the golden ratio.
double loop_radius(int k, int j, const AbdomenDimensions& d) {
  const double x = std::fmod(0.618034 * (3 * k + j) + 0.25, 1.0);
  return d.bowel_radius_min_m + x * (d.bowel_radius_max_m - d.bowel_radius_min_m);
}

// Ring k's loops (staggered against the ring inside it) and the fat in every other gap.
void append_ring(Scenery& s, const PlaneFrame& f, const AbdomenDimensions& d, int k, double base) {
  const double r_max = d.bowel_radius_max_m;
  const double gap = 2.0 * r_max + 0.006;  // arc length between two loops' ends, m
  Loop l;
  l.ring = {f.half, base + 0.5 * d.wiggle_m};
  l.base = base;
  l.wiggle = d.wiggle_m;
  const double length = l.ring.length();
  const int loops = std::max(2, static_cast<int>(std::lround(length / (d.loop_length_m + gap))));
  const double period = length / loops;
  l.waves = 2 * loops + 1;
  l.phase = 0.9 * k;
  for (int j = 0; j < loops; ++j) {
    l.from = period * (j + 0.37 * k);
    l.to = l.from + period - gap;
    l.radius = loop_radius(k, j, d);
    append_loop(s, l, f, d);
    if ((j + k) % 2 != 0) continue;
    // Fat in the gap after this loop, kept as far from the footprint as the bowel.
    const V3 abc(std::min(0.5 * gap + 0.012, 0.03), 1.1 * r_max, 0.007);
    const double centre = l.to + 0.5 * gap;
    const RingPoint p = ring_point(l.ring, centre);
    const double reach = std::max(abc.x(), abc.y());
    const double off = std::max(l.offset(centre), d.bowel_clearance_m + reach + 0.001);
    const V3 t = f.in_plane(V2(-p.dir.y(), p.dir.x()));
    append_lobule(s, f, p.q + off * p.dir, t, abc);
  }
}

void append_bowel(Scenery& s, const PlaneFrame& f, const AbdomenDimensions& d) {
  const double r_max = d.bowel_radius_max_m;
  double base = d.bowel_clearance_m + r_max;
  for (int k = 0; k < d.bowel_rings; ++k) {
    append_ring(s, f, d, k, base);
    base += 2.0 * r_max + d.wiggle_m + 0.002;  // the next ring clears this one's meander
  }
}

template <class T>
void hash_bytes(const std::vector<T>& v, std::uint64_t& h) {
  const auto* bytes = reinterpret_cast<const unsigned char*>(v.data());
  for (std::size_t i = 0; i < v.size() * sizeof(T); ++i) {
    h ^= bytes[i];
    h *= 1099511628211ULL;  // FNV-1a prime
  }
}

}  // namespace

Scenery make_abdomen(const AbdomenPlacement& placement, const AbdomenDimensions& dims) {
  const PlaneFrame f = plane_frame(placement);
  Scenery s;
  // Bowel and fat first: drawn in this order, they hide most of the wall behind them before its
  // fragments are shaded (early depth test), which counts on software GL.
  append_bowel(s, f, dims);
  append_wall(s, f, dims);
  s.version = content_version(s);
  return s;
}

std::uint64_t content_version(const Scenery& scenery) {
  if (scenery.empty()) return 0;
  std::uint64_t h = 14695981039346656037ULL;  // FNV-1a offset basis
  hash_bytes(scenery.pos, h);
  hash_bytes(scenery.nrm, h);
  hash_bytes(scenery.tri, h);
  hash_bytes(scenery.material, h);
  return h == 0 ? 1 : h;
}

}  // namespace serosa::render

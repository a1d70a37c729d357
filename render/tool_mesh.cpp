// Instrument meshes (see tool_mesh.h).
#include "render/tool_mesh.h"

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <tuple>

#include "engine/clip.h"
#include "engine/endoloop.h"
#include "engine/hook.h"
#include "engine/stapler.h"
#include "engine/tool_geometry.h"
#include "render/icosphere.h"

namespace serosa::render {
namespace {

using V3 = Eigen::Vector3f;

V3 vec(const std::array<float, 3>& a) { return {a[0], a[1], a[2]}; }
std::array<float, 3> arr(const V3& v) { return {v.x(), v.y(), v.z()}; }

constexpr std::array<float, 4> kShaftMaterial{0.10f, 0.10f, 0.11f, 0.55f};  // black coating
constexpr std::array<float, 4> kSteelMaterial{0.66f, 0.68f, 0.72f, 0.95f};  // polished steel
constexpr std::array<float, 4> kClipMaterial{0.78f, 0.76f, 0.70f, 0.9f};    // titanium
constexpr std::array<float, 4> kSutureMaterial{0.55f, 0.42f, 0.75f, 0.5f};  // violet polydioxanone
constexpr std::array<float, 4> kBloodMaterial{0.42f, 0.02f, 0.03f, 0.9f};   // fresh arterial blood
constexpr float kSutureRadius = 3e-4f;  // a 2-0 suture with some slack, m
constexpr std::array<float, 4> kCartridgeMaterial{0.22f, 0.36f, 0.62f, 0.4f};  // a blue reload
constexpr std::array<float, 4> kGuideMaterial{0.45f, 0.18f, 0.78f, 0.2f};      // marker violet
constexpr std::array<float, 4> kActiveMaterial{0.20f, 0.95f, 0.35f, 0.3f};     // the active collar
constexpr std::array<float, 4> kCueMaterial{0.05f, 0.05f, 0.06f, 0.0f};        // a shadow's dark
constexpr std::array<float, 4> kTouchMaterial{1.0f, 0.85f, 0.10f, 0.3f};       // contact: amber

std::uint32_t add_vertex(ToolMesh& m, const V3& p, const V3& n, const std::array<float, 4>& mat) {
  const auto id = static_cast<std::uint32_t>(m.num_vertices());
  m.pos.insert(m.pos.end(), {p.x(), p.y(), p.z()});
  const V3 u = n.norm() > 1e-12f ? V3(n.normalized()) : V3(0.0f, 0.0f, 1.0f);
  m.nrm.insert(m.nrm.end(), {u.x(), u.y(), u.z()});
  m.material.insert(m.material.end(), mat.begin(), mat.end());
  return id;
}

// A flat quad a b c d (any winding) facing away from `inside`.
void add_quad(ToolMesh& m, const std::array<V3, 4>& q, const V3& inside,
              const std::array<float, 4>& mat) {
  V3 n = (q[2] - q[0]).cross(q[3] - q[1]);
  const V3 centre = 0.25f * (q[0] + q[1] + q[2] + q[3]);
  const bool flip = n.dot(centre - inside) < 0.0f;
  if (flip) n = -n;
  std::array<std::uint32_t, 4> id{};
  for (int k = 0; k < 4; ++k) id[k] = add_vertex(m, q[k], n, mat);
  if (flip) {
    m.tri.insert(m.tri.end(), {id[0], id[2], id[1], id[0], id[3], id[2]});
  } else {
    m.tri.insert(m.tri.end(), {id[0], id[1], id[2], id[0], id[2], id[3]});
  }
}

// One jaw: rectangular sections along `dir` from `base`, each centred at base + u dir +
// offset(u), half extents hw(u) along `wdir` and ht(u) along `up`; flat-shaded sides and caps.
template <class Centre, class HalfW, class HalfT>
void add_jaw(ToolMesh& m, const V3& base, const V3& dir, const V3& wdir, const V3& up, float length,
             Centre centre, HalfW hw, HalfT ht, const std::array<float, 4>& mat) {
  constexpr int kSections = 8;
  std::array<std::array<V3, 4>, kSections + 1> ring{};
  std::array<V3, kSections + 1> mid{};
  for (int i = 0; i <= kSections; ++i) {
    const float s = static_cast<float>(i) / kSections;
    const V3 c = base + s * length * dir + centre(s);
    mid[i] = c;
    const float w = hw(s), t = ht(s);
    ring[i] = {c - w * wdir - t * up, c + w * wdir - t * up, c + w * wdir + t * up,
               c - w * wdir + t * up};
  }
  for (int i = 0; i < kSections; ++i) {
    const V3 inside = 0.5f * (mid[i] + mid[i + 1]);
    for (int k = 0; k < 4; ++k) {
      const int k1 = (k + 1) % 4;
      add_quad(m, {ring[i][k], ring[i][k1], ring[i + 1][k1], ring[i + 1][k]}, inside, mat);
    }
  }
  add_quad(m, ring[0], mid[0] + 0.01f * length * dir, mat);
  add_quad(m, ring[kSections], mid[kSections] - 0.01f * length * dir, mat);
}

void add_shaft(ToolMesh& m, const V3& a, const V3& b, const V3& side, const V3& up, float r,
               int segments, const std::array<float, 4>& material = kShaftMaterial) {
  segments = std::max(segments, 3);
  const auto base = static_cast<std::uint32_t>(m.num_vertices());
  for (int i = 0; i < segments; ++i) {
    const float phi = 2.0f * 3.14159265f * static_cast<float>(i) / static_cast<float>(segments);
    const V3 n = std::cos(phi) * side + std::sin(phi) * up;
    add_vertex(m, a + r * n, n, material);
    add_vertex(m, b + r * n, n, material);
  }
  const V3 axis = (b - a).normalized();
  const auto seg = static_cast<std::uint32_t>(segments);
  for (std::uint32_t i = 0; i < seg; ++i) {
    const std::uint32_t j = (i + 1) % seg;
    const std::uint32_t a0 = base + 2 * i, b0 = a0 + 1, a1 = base + 2 * j, b1 = a1 + 1;
    // side x up = axis: counter-clockwise around +axis, so (a0, a1, b1) faces outward.
    m.tri.insert(m.tri.end(), {a0, a1, b1, a0, b1, b0});
  }
  // Caps: fans around a centre vertex, normals along the axis.
  for (int end = 0; end < 2; ++end) {
    const V3 c = end == 0 ? a : b;
    const V3 n = end == 0 ? V3(-axis) : axis;
    const std::uint32_t centre = add_vertex(m, c, n, material);
    const auto first = static_cast<std::uint32_t>(m.num_vertices());
    for (int i = 0; i < segments; ++i) {
      const float phi = 2.0f * 3.14159265f * static_cast<float>(i) / static_cast<float>(segments);
      add_vertex(m, c + r * (std::cos(phi) * side + std::sin(phi) * up), n, material);
    }
    for (std::uint32_t i = 0; i < seg; ++i) {
      const std::uint32_t p = first + i, q = first + (i + 1) % seg;
      if (end == 0) {
        m.tri.insert(m.tri.end(), {centre, q, p});
      } else {
        m.tri.insert(m.tri.end(), {centre, p, q});
      }
    }
  }
}

// A box: centre c, half extents along the orthonormal axes a, b, d.
void add_box(ToolMesh& m, const V3& c, const V3& a, const V3& b, const V3& d, float ha, float hb,
             float hd, const std::array<float, 4>& mat) {
  for (int s = -1; s <= 1; s += 2) {
    const float f = static_cast<float>(s);
    for (const auto& [n, u, v, hn, hu, hv] :
         {std::tuple{a, b, d, ha, hb, hd}, std::tuple{b, d, a, hb, hd, ha},
          std::tuple{d, a, b, hd, ha, hb}}) {
      const V3 fc = c + f * hn * n;
      add_quad(
          m,
          {fc - hu * u - hv * v, fc + hu * u - hv * v, fc + hu * u + hv * v, fc - hu * u + hv * v},
          c, mat);
    }
  }
}

}  // namespace

void append_guide_mesh(const std::vector<std::array<float, 3>>& line, ToolMesh& out) {
  for (std::size_t i = 0; i + 1 < line.size(); ++i) {
    const V3 a = vec(line[i]), b = vec(line[i + 1]);
    if ((b - a).norm() < 1e-9f) continue;
    const V3 axis = (b - a).normalized();
    const V3 side = axis.unitOrthogonal();
    add_shaft(out, a, b, side, axis.cross(side), kGuideRadius, 12, kGuideMaterial);
  }
}

namespace {

// A suture ring: a chain of thin cylinders round `centre` in the plane normal to `axis`.
void add_ring(ToolMesh& m, const V3& centre, const V3& axis, const V3& u, float radius,
              const std::array<float, 4>& mat) {
  const V3 w = axis.cross(u);
  constexpr int kSegments = 24;
  constexpr float kTwoPi = 6.28318531f;
  for (int k = 0; k < kSegments; ++k) {
    const float a0 = kTwoPi * static_cast<float>(k) / kSegments;
    const float a1 = kTwoPi * static_cast<float>(k + 1) / kSegments;
    const V3 p0 = centre + radius * (std::cos(a0) * u + std::sin(a0) * w);
    const V3 p1 = centre + radius * (std::cos(a1) * u + std::sin(a1) * w);
    const V3 t = (p1 - p0).normalized();
    add_shaft(m, p0, p1, axis, t.cross(axis), kSutureRadius, 6, mat);
  }
}

// A flat annulus about `centre` facing `normal`, inner and outer radius, m (culling is off: seen
// from both sides).
void add_annulus(ToolMesh& m, const V3& centre, const V3& normal, float inner, float outer,
                 const std::array<float, 4>& mat) {
  const V3 u = normal.unitOrthogonal();
  const V3 w = normal.cross(u);
  constexpr int kSegments = 32;
  constexpr float kTwoPi = 6.28318531f;
  const auto base = static_cast<std::uint32_t>(m.num_vertices());
  for (int k = 0; k < kSegments; ++k) {
    const float a = kTwoPi * static_cast<float>(k) / kSegments;
    const V3 d = std::cos(a) * u + std::sin(a) * w;
    add_vertex(m, centre + inner * d, normal, mat);
    add_vertex(m, centre + outer * d, normal, mat);
  }
  const auto seg = static_cast<std::uint32_t>(kSegments);
  for (std::uint32_t k = 0; k < seg; ++k) {  // u x w = normal: counter-clockwise from +normal
    const std::uint32_t i0 = base + 2 * k, o0 = i0 + 1;
    const std::uint32_t i1 = base + 2 * ((k + 1) % seg), o1 = i1 + 1;
    m.tri.insert(m.tri.end(), {i0, o0, o1, i0, o1, i1});
  }
}

}  // namespace

void append_depth_cue(const RenderTool& tool, ToolMesh& out) {
  if (!tool.has_tissue || !(tool.tissue_distance_m < kDepthCueRange)) return;
  const V3 n = vec(tool.tissue_normal);
  if (!(n.norm() > 1e-6f)) return;
  const float d = std::max(tool.tissue_distance_m, 0.0f);
  const bool touching = tool.tissue_distance_m <= kTouchDistance;
  const float outer = kDepthCueMinRadius + kDepthCueSpread * d;
  const float width = touching ? 1.0e-3f : 0.6e-3f;
  add_annulus(out, vec(tool.tissue_point) + kDepthCueLift * n.normalized(), n.normalized(),
              std::max(outer - width, 0.0f), outer, touching ? kTouchMaterial : kCueMaterial);
}

namespace {

// A staple line: kStapleRows staggered rows of closed staples along a -> b, each staple a crown
// and its clinched legs, one each side of the pressed tissue (kStapleGap apart).
void add_staple_line(ToolMesh& m, const V3& a, const V3& b, const V3& across_hint) {
  const V3 along = (b - a).normalized();
  V3 across = across_hint - across_hint.dot(along) * along;
  if (!(across.norm() > 1e-6f)) across = along.unitOrthogonal();
  across.normalize();
  const V3 pin = along.cross(across);
  const float length = (b - a).norm();
  const float ht = 0.5f * kStapleWireThickness;
  const float off = static_cast<float>(0.5 * kStapleGap) + ht;  // crown and clinch off the line
  const float row = static_cast<float>(kStapleLineHalfWidth) * 2.0f / 3.0f;
  for (int r = -1; r <= 1; ++r) {
    const float stagger = r == 0 ? 0.5f * kStaplePitch : 0.0f;
    for (float u = stagger + 0.5f * kStapleCrown; u + 0.5f * kStapleCrown <= length;
         u += kStaplePitch) {
      const V3 c = a + u * along + static_cast<float>(r) * row * pin;
      for (int s = -1; s <= 1; s += 2)
        add_box(m, c + static_cast<float>(s) * off * across, along, pin, across,
                0.5f * kStapleCrown, ht, ht, kClipMaterial);
    }
  }
}

}  // namespace

void append_clip_mesh(const RenderClip& clip, ToolMesh& out) {
  const V3 a = vec(clip.start), b = vec(clip.end);
  if (!((b - a).norm() > 1e-9f)) return;
  if (clip.staple) {
    add_staple_line(out, a, b, vec(clip.across));
    return;
  }
  if (clip.loop) {
    const V3 axis = (b - a).normalized();
    V3 u = vec(clip.across) - vec(clip.across).dot(axis) * axis;
    if (!(u.norm() > 1e-6f)) u = axis.unitOrthogonal();
    add_ring(out, 0.5f * (a + b), axis, u.normalized(), clip.radius + kSutureRadius,
             kSutureMaterial);
    return;
  }
  const V3 along = (b - a).normalized();
  V3 across = vec(clip.across) - vec(clip.across).dot(along) * along;
  if (!(across.norm() > 1e-6f)) across = along.unitOrthogonal();
  across.normalize();
  const V3 pin = along.cross(across);
  const float half_len = 0.5f * (b - a).norm();
  const float hw = static_cast<float>(kClipHalfWidth);
  const float ht = 0.5f * kClipLegThickness;
  const float leg = static_cast<float>(0.5 * kClipGap) + ht;  // legs' centres off the line
  const V3 mid = 0.5f * (a + b);
  for (int s = -1; s <= 1; s += 2)
    add_box(out, mid + static_cast<float>(s) * leg * across, along, pin, across, half_len, hw, ht,
            kClipMaterial);
  add_box(out, b + ht * along, along, pin, across, ht, hw, leg + ht, kClipMaterial);  // the crown
}

namespace {

// A blob of blood: a sphere of `radius` about `at`, squashed along the unit `axis` to `flat` of
// its radius (1: round). An ellipsoid's normal at the sphere's n is flat x n_across + n_along.
void add_blood_blob(ToolMesh& out, const V3& at, float radius, const V3& axis, float flat,
                    const std::array<float, 4>& material) {
  static const TriMesh unit = icosphere(2);
  const auto base = static_cast<std::uint32_t>(out.num_vertices());
  for (std::size_t v = 0; v + 2 < unit.pos.size(); v += 3) {
    const V3 n(unit.pos[v], unit.pos[v + 1], unit.pos[v + 2]);
    const V3 along = n.dot(axis) * axis;
    const V3 across = n - along;
    add_vertex(out, at + radius * (across + flat * along), (flat * across + along).normalized(),
               material);
  }
  for (std::uint32_t id : unit.tri) out.tri.push_back(base + id);
}

constexpr float kDropRadiusM = 0.0008f;  // one droplet of the stream, m

}  // namespace

void append_bleed_mesh(const RenderBleed& bleed, ToolMesh& out) {
  if (bleed.radius > 0.0f)
    add_blood_blob(out, vec(bleed.at), bleed.radius, V3::UnitZ(), 1.0f, kBloodMaterial);
  for (const auto& p : bleed.stream)
    add_blood_blob(out, vec(p), kDropRadiusM, V3::UnitZ(), 1.0f, kBloodMaterial);
}

void ToolMesh::clear() {
  pos.clear();
  nrm.clear();
  material.clear();
  tri.clear();
}

ToolFrame tool_frame(const RenderTool& tool, const ToolDimensions& dims) {
  Eigen::Quaternionf q(tool.quat_wxyz[0], tool.quat_wxyz[1], tool.quat_wxyz[2], tool.quat_wxyz[3]);
  if (q.norm() < 1e-6f) q = Eigen::Quaternionf::Identity();
  q.normalize();
  const Eigen::Matrix3f r = q.toRotationMatrix();
  const V3 tip = vec(tool.tip);
  V3 axis = r.col(2);
  if (tool.has_trocar) {
    const V3 d = tip - vec(tool.trocar);
    if (d.norm() > 1e-6f) axis = d.normalized();
  }
  V3 up = r.col(1) - r.col(1).dot(axis) * axis;
  if (up.norm() < 1e-4f) up = axis.unitOrthogonal();
  up.normalize();
  const V3 side = up.cross(axis);
  // A stapler pivots where the simulation has it (engine/stapler.h): its jaws reach on past
  // the tip.
  const float jaw = tool.kind == RenderTool::Kind::kScissors  ? dims.scissors_blade
                    : tool.kind == RenderTool::Kind::kStapler ? static_cast<float>(kJawLength)
                                                              : dims.grasper_jaw;
  const V3 hinge = tip - jaw * axis;
  const V3 start = tool.has_trocar ? V3(vec(tool.trocar) - dims.shaft_outside * axis)
                                   : V3(hinge - dims.shaft_no_trocar * axis);
  ToolFrame f;
  f.axis = arr(axis);
  f.up = arr(up);
  f.side = arr(side);
  f.hinge = arr(hinge);
  f.shaft_start = arr(start);
  return f;
}

void append_tool_mesh(const RenderTool& tool, ToolMesh& out, const ToolDimensions& dims) {
  const ToolFrame f = tool_frame(tool, dims);
  const V3 axis = vec(f.axis), up = vec(f.up), side = vec(f.side), hinge = vec(f.hinge);
  const float r = dims.shaft_radius;
  // The shaft stops where the jaws begin (the hinge sits just inside its end).
  add_shaft(out, vec(f.shaft_start), hinge + 0.3f * r * axis, side, up, r, dims.shaft_segments);
  if (tool.active)  // a coloured collar behind the jaws: the instrument the mouse steers
    add_shaft(out, hinge - 0.014f * axis, hinge - 0.006f * axis, side, up, 1.15f * r,
              dims.shaft_segments, kActiveMaterial);

  if (tool.kind == RenderTool::Kind::kEndoloop) {  // the pusher's end, the knot, the open loop
    const V3 tip = vec(tool.tip);
    add_shaft(out, hinge, tip, side, up, 0.9e-3f, 10, kSteelMaterial);
    const float ring = static_cast<float>(kLoopRadius) *
                       std::clamp(tool.jaw_rad / static_cast<float>(kLoopArmRad), 0.1f, 1.0f);
    add_ring(out, tip + ring * side, axis, -side, ring, kSutureMaterial);
    return;
  }
  if (tool.kind == RenderTool::Kind::kHook) {  // a bare steel stem, bent at the tip
    const V3 tip = vec(tool.tip);
    add_shaft(out, hinge, tip, side, up, 0.5e-3f, 10, kSteelMaterial);
    add_shaft(out, tip - 0.5e-3f * side, tip + static_cast<float>(kHookCrook) * side, axis,
              side.cross(axis), 0.35e-3f, 10, kSteelMaterial);
    return;
  }
  const float a = 0.5f * std::clamp(tool.jaw_rad, 0.0f, 3.14159265f);
  const float ca = std::cos(a), sa = std::sin(a);
  // Jaw A opens towards +side, jaw B towards -side; wdir points away from the other jaw.
  const V3 dir_a = ca * axis + sa * side, w_a = ca * side - sa * axis;
  const V3 dir_b = ca * axis - sa * side, w_b = -(ca * side + sa * axis);
  if (tool.kind == RenderTool::Kind::kStapler) {
    // The cartridge (jaw A) is deep, the anvil (jaw B) thin; both span the staple lines along up
    // and meet on the axis when closed.
    const float len = static_cast<float>(kCartridgeLength);
    const auto wide = [](float) { return 3.5e-3f; };
    const auto deep = [](float) { return 1.4e-3f; };
    const auto thin = [](float) { return 0.7e-3f; };
    const V3 oa = 1.5e-3f * w_a, ob = 0.8e-3f * w_b;
    add_jaw(
        out, hinge, dir_a, w_a, up, len, [&](float) -> V3 { return oa; }, deep, wide,
        kCartridgeMaterial);
    add_jaw(
        out, hinge, dir_b, w_b, up, len, [&](float) -> V3 { return ob; }, thin, wide,
        kSteelMaterial);
  } else if (tool.kind == RenderTool::Kind::kScissors) {
    const float len = dims.scissors_blade;
    const float off = 0.45e-3f;  // blades side by side along `up`, 0.9 mm apart
    const auto half_w = [](float s) { return 1.3e-3f + (0.35e-3f - 1.3e-3f) * s; };
    const auto half_t = [](float) { return 0.4e-3f; };
    // Slightly curved (Metzenbaum), both towards +side.
    const auto curve = [&](float o) {
      return [&, o](float s) -> V3 { return o * up + 1.2e-3f * s * s * side; };
    };
    add_jaw(out, hinge, dir_a, w_a, up, len, curve(off), half_w, half_t, kSteelMaterial);
    add_jaw(out, hinge, dir_b, w_b, up, len, curve(-off), half_w, half_t, kSteelMaterial);
  } else {
    const float len = dims.grasper_jaw;
    // Each jaw on its own side of the axis: its body spans 0.1..1.5 mm away from the other jaw.
    const auto half_w = [](float) { return 0.7e-3f; };
    const auto half_t = [](float s) { return 1.7e-3f + (1.2e-3f - 1.7e-3f) * s; };
    const V3 oa = 0.8e-3f * w_a, ob = 0.8e-3f * w_b;
    add_jaw(
        out, hinge, dir_a, w_a, up, len, [&](float) -> V3 { return oa; }, half_w, half_t,
        kSteelMaterial);
    add_jaw(
        out, hinge, dir_b, w_b, up, len, [&](float) -> V3 { return ob; }, half_w, half_t,
        kSteelMaterial);
  }
}

}  // namespace serosa::render

#include "app/render_frame_from_surface.h"

#include <algorithm>
#include <array>
#include <initializer_list>

#include "engine/board_normal.h"
#include "engine/scope_view.h"
#include "engine/tool_geometry.h"
#include "render/camera.h"
#include "surface/surface_normals.h"

namespace serosa::app {
namespace {

std::array<float, 3> to_float(const std::array<double, 3>& a) {
  return {static_cast<float>(a[0]), static_cast<float>(a[1]), static_cast<float>(a[2])};
}

std::array<float, 3> to_float(const Vec3& v) {
  return {static_cast<float>(v.x()), static_cast<float>(v.y()), static_cast<float>(v.z())};
}

std::array<float, 4> to_float(const std::array<double, 4>& a) {
  return {static_cast<float>(a[0]), static_cast<float>(a[1]), static_cast<float>(a[2]),
          static_cast<float>(a[3])};
}

// Unique tet edges (e x 2), sorted.
void tet_edges(const TetMesh& mesh, std::vector<std::uint32_t>& out) {
  out.clear();
  std::vector<std::array<std::uint32_t, 2>> e;
  e.reserve(6 * mesh.tets.size());
  for (const Tet& t : mesh.tets)
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b) {
        auto u = static_cast<std::uint32_t>(t[a]), v = static_cast<std::uint32_t>(t[b]);
        e.push_back({std::min(u, v), std::max(u, v)});
      }
  std::sort(e.begin(), e.end());
  e.erase(std::unique(e.begin(), e.end()), e.end());
  out.reserve(2 * e.size());
  for (const auto& [u, v] : e) {
    out.push_back(u);
    out.push_back(v);
  }
}

// The pattern's rest positions of the render vertices (after the n node prefix, which takes its
// nodes' own), and the wound's rim: a cut face's corner whose node also lies on an uncut face.
void fill_rest_and_rim(const TetMesh& mesh, const surface::SurfaceMesh& surface,
                       const surface::RenderVertices& rv, const std::vector<std::uint8_t>& marks,
                       std::size_t n, render::RenderFrame& frame) {
  const std::size_t v = rv.node.size();
  frame.rest.resize(3 * (n + v));
  for (std::size_t i = 0; i < n + v; ++i) {
    const auto node = i < n ? i : static_cast<std::size_t>(rv.node[i - n]);
    for (int k = 0; k < 3; ++k) frame.rest[3 * i + k] = static_cast<float>(mesh.rest[node][k]);
  }
  std::vector<std::uint8_t> on_uncut(mesh.x.size(), 0);
  for (std::size_t i = 0; i < surface.faces.size(); ++i)
    if (marks[i] != 1)
      for (const std::int32_t node : surface.faces[i]) on_uncut[static_cast<std::size_t>(node)] = 1;
  frame.rim.assign(n + v, 0.0f);
  for (std::size_t i = 0; i < surface.faces.size(); ++i) {
    if (marks[i] != 1) continue;
    for (const std::int32_t r : rv.tris[i])
      if (on_uncut[static_cast<std::size_t>(rv.node[static_cast<std::size_t>(r)])] != 0)
        frame.rim[n + static_cast<std::size_t>(r)] = 1.0f;
  }
}

// Each vertex's node's stain of blood (none without a stain).
void fill_stain(const surface::RenderVertices& rv, std::size_t n, const std::vector<float>* stain,
                render::RenderFrame& frame) {
  if (stain == nullptr || stain->empty()) {
    frame.stain.clear();
    return;
  }
  const auto of = [&](std::size_t node) { return node < stain->size() ? (*stain)[node] : 0.0f; };
  frame.stain.resize(n + rv.node.size());
  for (std::size_t i = 0; i < n; ++i) frame.stain[i] = of(i);
  for (std::size_t i = 0; i < rv.node.size(); ++i)
    frame.stain[n + i] = of(static_cast<std::size_t>(rv.node[i]));
}

}  // namespace

void fill_render_frame(const TetMesh& mesh, const surface::SurfaceMesh& surface,
                       const std::map<int, std::string>& group_names, bool with_edges,
                       render::RenderFrame& frame, const std::vector<std::uint8_t>* coagulated,
                       std::uint64_t coagulated_version, const std::vector<float>* stain) {
  const std::size_t f = surface.faces.size();
  // Wound flags: from the surface when it has them (sized like its faces).
  std::vector<std::uint8_t> cut = surface.face_cut;
  if (cut.size() != f) cut.assign(f, 0);
  std::vector<std::uint8_t> marks = cut;  // the wound, and where a hook coagulated
  if (coagulated != nullptr && !coagulated->empty()) {
    const auto marked = [&](std::int32_t n) {
      return n >= 0 && static_cast<std::size_t>(n) < coagulated->size() &&
             (*coagulated)[static_cast<std::size_t>(n)] != 0;
    };
    for (std::size_t i = 0; i < f; ++i)
      if (marked(surface.faces[i][0]) && marked(surface.faces[i][1]) && marked(surface.faces[i][2]))
        marks[i] = 2;
  }
  frame.material_version = coagulated_version;

  // Render vertices with split normals (the surface module's rule needs sized flags).
  surface::SurfaceMesh flagged;
  const surface::SurfaceMesh* s = &surface;
  if (surface.face_cut.size() != f) {
    flagged = surface;
    flagged.face_cut = cut;
    s = &flagged;
  }
  surface::RenderVertices rv;
  surface::compute_render_vertices(*s, mesh.x, surface::NormalOptions{}, rv);

  const std::size_t n = with_edges ? mesh.x.size() : 0;  // node prefix for the tet edges
  const std::size_t v = rv.node.size();
  frame.pos.resize(3 * (n + v));
  frame.nrm.assign(3 * (n + v), 0.0f);
  for (std::size_t i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) frame.pos[3 * i + k] = static_cast<float>(mesh.x[i][k]);
  for (std::size_t i = 0; i < v; ++i) {
    const Vec3& p = mesh.x[static_cast<std::size_t>(rv.node[i])];
    for (int k = 0; k < 3; ++k) {
      frame.pos[3 * (n + i) + k] = static_cast<float>(p[k]);
      frame.nrm[3 * (n + i) + k] = static_cast<float>(rv.normal[i][k]);
    }
  }
  fill_rest_and_rim(mesh, surface, rv, marks, n, frame);
  fill_stain(rv, n, stain, frame);
  frame.tri.resize(3 * f);
  for (std::size_t i = 0; i < f; ++i)
    for (int k = 0; k < 3; ++k)
      frame.tri[3 * i + k] =
          static_cast<std::uint32_t>(n + static_cast<std::size_t>(rv.tris[i][k]));
  frame.tri_group = surface.face_group;
  frame.tri_cut = std::move(marks);

  // Tet edges change only with the topology: keep them across frames otherwise.
  const bool edges_stale =
      frame.edges.empty() || frame.topology_version != surface.topology_version;
  frame.topology_version = surface.topology_version;
  if (!with_edges) frame.edges.clear();
  if (with_edges && edges_stale) tet_edges(mesh, frame.edges);

  frame.group_names.clear();
  if (!group_names.empty()) {
    frame.group_names.resize(static_cast<std::size_t>(group_names.rbegin()->first) + 1);
    for (const auto& [id, name] : group_names)
      if (id >= 0) frame.group_names[static_cast<std::size_t>(id)] = name;
  }
}

namespace {
constexpr double kClipMarkHalfLength = 0.004;  ///< m: the clip target's pin, either side of it
constexpr double kBleedRadius = 0.005;         ///< m: the pool a cut artery makes ...
constexpr double kBleedGrowS = 2.0;            ///< s: ... in this long
}  // namespace

namespace {

constexpr int kStreamDrops = 14;          ///< droplets drawn along the stream
constexpr double kStreamStepS = 0.008;    ///< time of flight between two of them, s
constexpr double kStreamSpeedMps = 0.45;  ///< the stream's speed at the top of a pulse, m/s

// The stream from a cut end: droplets on the ballistic path of blood leaving it upwards (against
// gravity, leaning sideways so that a scope above sees its arc) at a speed that follows the
// pulse, down to the pool's plane.
std::vector<std::array<float, 3>> stream(const Blood& b, const Vec3& gravity) {
  std::vector<std::array<float, 3>> out;
  if (b.pulse <= 0.0 || gravity.norm() <= 0.0) return out;
  const Vec3 up = -gravity.normalized();
  const Vec3 dir = (0.8 * up + up.unitOrthogonal()).normalized();
  const Vec3 v0 = kStreamSpeedMps * b.pulse * dir;
  for (int i = 1; i <= kStreamDrops; ++i) {
    const double t = i * kStreamStepS;
    const Vec3 p = b.source_m + t * v0 + 0.5 * t * t * gravity;
    if ((p - b.pool_m).dot(b.pool_normal) < 0.0) break;
    out.push_back(to_float(p));
  }
  return out;
}

// The tissue between a tool's open jaws: the surface corners within kJawSlabM of the jaws' plane
// between them, and the diagonal of their box in that plane, m (0 with fewer than two).
constexpr double kJawSlabM = 0.0015;
constexpr double kJawsOpenRad = 0.2;

float tissue_in_jaws(const SimState& state, const ToolState& tool) {
  if (tool.jaw_rad < kJawsOpenRad) return 0.0f;
  const ToolFrame f = tool_frame(tool);
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(1e9), hi = -lo;
  int n = 0;
  for (const Tri& face : state.shared.surface.faces) {
    for (const std::int32_t v : face) {
      const Vec3& p = state.mesh.x[static_cast<std::size_t>(v)];
      if (!between_jaws(f, tool.jaw_rad, p, kJawSlabM)) continue;
      const Eigen::Vector2d q((p - f.hinge).dot(f.forward), (p - f.hinge).dot(f.side));
      lo = lo.cwiseMin(q);
      hi = hi.cwiseMax(q);
      ++n;
    }
  }
  return n >= 2 ? static_cast<float>((hi - lo).norm()) : 0.0f;
}

}  // namespace

namespace {

// Blood: with effect "bleeding", each bleeding's drop, stream and pool as the stage publishes
// them; without it, a drop that wells up over kBleedGrowS to kBleedRadius where it was cut.
void fill_render_bleeds(const Scene& scene, const SimState& state, render::RenderFrame& frame) {
  frame.bleeds.clear();
  for (std::size_t k = 0; k < state.shared.bleeds.size(); ++k) {
    const auto& [where, since] = state.shared.bleeds[k];
    const double grown = std::clamp((state.time_s - since) / kBleedGrowS, 0.0, 1.0);
    render::RenderBleed rb;
    rb.at = to_float(where);
    rb.radius = static_cast<float>(kBleedRadius * (0.2 + 0.8 * grown));
    if (k < state.shared.blood.size()) {
      const Blood& b = state.shared.blood[k];
      rb.at = to_float(b.source_m);
      rb.radius = static_cast<float>(0.3 * kBleedRadius);
      rb.pool = to_float(b.pool_m);
      rb.pool_normal = to_float(b.pool_normal);
      rb.pool_radius = static_cast<float>(b.pool_radius_m);
      rb.stream = stream(b, scene.settings.gravity_mps2);
    }
    frame.bleeds.push_back(std::move(rb));
  }
}

}  // namespace

void fill_taenia(const TetMesh& mesh, const std::map<int, std::string>& names,
                 render::RenderFrame& frame) {
  frame.taenia_axis = {0.0f, 0.0f, 0.0f};
  const auto named = [&](std::uint16_t g, std::initializer_list<const char*> which) {
    const auto it = names.find(g);
    if (it == names.end()) return false;
    for (const char* w : which)
      if (it->second == w) return true;
    return false;
  };
  std::vector<std::uint8_t> in(mesh.rest.size(), 0);  // bit 0: bowel, bit 1: appendix
  for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
    const std::uint8_t bit = named(mesh.group[t], {"cecum", "colon"}) ? 1
                             : named(mesh.group[t], {"appendix"})     ? 2
                                                                      : 0;
    if (bit != 0)
      for (const std::int32_t v : mesh.tets[t]) in[static_cast<std::size_t>(v)] |= bit;
  }
  Vec3 bowel = Vec3::Zero(), appendix = Vec3::Zero(), base = Vec3::Zero();
  double nb = 0.0, na = 0.0, ns = 0.0;
  for (std::size_t i = 0; i < in.size(); ++i) {
    if ((in[i] & 1) != 0) {
      bowel += mesh.rest[i];
      nb += 1.0;
    }
    if ((in[i] & 2) != 0) {
      appendix += mesh.rest[i];
      na += 1.0;
    }
    if (in[i] == 3) {
      base += mesh.rest[i];
      ns += 1.0;
    }
  }
  if (nb == 0.0 || na == 0.0) return;
  const Vec3 centre = bowel / nb;
  const Vec3 axis = (ns > 0.0 ? Vec3(base / ns) : Vec3(appendix / na)) - centre;
  if (axis.norm() <= 0.0) return;
  frame.taenia_centre = to_float(centre);
  frame.taenia_axis = to_float(Vec3(axis.normalized()));
}

std::map<int, std::string> drawn_group_names(const Scene& scene, std::map<int, std::string> names) {
  for (auto& [id, name] : names)
    if (const auto look = scene.render.looks.find(name); look != scene.render.looks.end())
      name = look->second;
  return names;
}

void fill_render_tools(const Scene& scene, const SimState& state, render::RenderFrame& frame) {
  frame.tools.clear();
  frame.guide.clear();
  frame.clips.clear();
  for (const Clip& c : state.shared.clips) {
    render::RenderClip rc;
    rc.start = to_float(c.end(0));
    rc.end = to_float(c.end(1));
    rc.across = to_float(Vec3(c.frame.col(0)));
    rc.loop = c.kind == Clip::Kind::kLoop;
    rc.staple = c.kind == Clip::Kind::kStaple;
    rc.radius = static_cast<float>(c.reach_m());
    frame.clips.push_back(rc);
  }
  fill_render_bleeds(scene, state, frame);
  frame.smoke.clear();
  for (const SmokePuff& p : state.shared.smoke)
    frame.smoke.push_back(
        {to_float(p.at_m), static_cast<float>(p.radius_m), static_cast<float>(p.density)});
  for (const Vec3& p : scene.metrics.planned_cut_m) frame.guide.push_back(to_float(p));
  if (scene.metrics.planned_cut_m.empty() && scene.metrics.clip_target_m) {
    const Vec3 up = board_normal(scene);
    for (const double s : {-kClipMarkHalfLength, kClipMarkHalfLength})
      frame.guide.push_back(to_float(Vec3(*scene.metrics.clip_target_m + s * up)));
  }
  for (std::size_t i = 0; i < scene.tools.size() && i < state.tools.size(); ++i) {
    const Tool& tool = scene.tools[i];
    if (tool.kind == ToolKind::kEndoscope) continue;
    const ToolState& in = state.tools[i];
    // A tool no device has posed yet (its input still the default: at the origin, or waiting in
    // its port, app/assemble_state.cpp) is not drawn.
    const std::array<double, 3> unposed =
        tool.trocar_m
            ? std::array<double, 3>{tool.trocar_m->x(), tool.trocar_m->y(), tool.trocar_m->z()}
            : std::array<double, 3>{0.0, 0.0, 0.0};
    if (in.tip_m == unposed && in.quat_wxyz == std::array<double, 4>{1.0, 0.0, 0.0, 0.0}) continue;
    render::RenderTool t;
    t.kind = tool.kind == ToolKind::kScissors      ? render::RenderTool::Kind::kScissors
             : tool.kind == ToolKind::kClipApplier ? render::RenderTool::Kind::kClipApplier
             : tool.kind == ToolKind::kHook        ? render::RenderTool::Kind::kHook
             : tool.kind == ToolKind::kEndoloop    ? render::RenderTool::Kind::kEndoloop
             : tool.kind == ToolKind::kStapler     ? render::RenderTool::Kind::kStapler
                                                   : render::RenderTool::Kind::kGrasper;
    t.tip = to_float(in.tip_m);
    t.quat_wxyz = to_float(in.quat_wxyz);
    t.jaw_rad = std::clamp(static_cast<float>(in.jaw_rad), 0.0f, 3.14159265f);
    t.scene_tool = static_cast<std::uint32_t>(i);
    t.tissue_in_jaws_m = tissue_in_jaws(state, in);
    const auto& planes = state.events.tissue_near;
    if (i < planes.size() && planes[i]) {
      const Vec3 p(planes[i]->point_m[0], planes[i]->point_m[1], planes[i]->point_m[2]);
      const Vec3 n(planes[i]->normal[0], planes[i]->normal[1], planes[i]->normal[2]);
      t.has_tissue = true;
      t.tissue_point = to_float(p);
      t.tissue_normal = to_float(n);
      t.tissue_distance_m =
          static_cast<float>((Vec3(in.tip_m[0], in.tip_m[1], in.tip_m[2]) - p).dot(n));
    }
    if (tool.trocar_m) {
      t.has_trocar = true;
      t.trocar = {static_cast<float>(tool.trocar_m->x()), static_cast<float>(tool.trocar_m->y()),
                  static_cast<float>(tool.trocar_m->z())};
    }
    frame.tools.push_back(t);
  }
}

std::optional<render::Camera> endoscope_view(const Scene& scene, const SimState& state) {
  for (std::size_t i = 0; i < scene.tools.size() && i < state.tools.size(); ++i) {
    if (scene.tools[i].kind != ToolKind::kEndoscope) continue;
    const ToolState& in = state.tools[i];
    if (!scope_posed(in)) return std::nullopt;
    // Still waiting in its port (assemble_state puts it there until a device drives it): it sees
    // the inside of the port, so the caller's own camera serves better.
    const auto& port = scene.tools[i].trocar_m;
    if (port && in.tip_m == std::array<double, 3>{port->x(), port->y(), port->z()} &&
        in.quat_wxyz == std::array<double, 4>{1.0, 0.0, 0.0, 0.0})
      return std::nullopt;
    return render::endoscope_camera(to_float(in.tip_m), to_float(in.quat_wxyz),
                                    static_cast<float>(scope_angle_deg(in)),
                                    static_cast<float>(kScopeFovDeg));
  }
  return std::nullopt;
}

}  // namespace serosa::app

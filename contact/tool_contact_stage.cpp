#include "contact/tool_contact_stage.h"

#include <algorithm>
#include <cmath>

#include "engine/geometry/point_triangle.h"
#include "engine/instrument_hold.h"
#include "engine/sim_state.h"
#include "engine/tool_geometry.h"

namespace serosa::contact {
namespace {

Mat3 frame_matrix(const ToolFrame& f) {
  Mat3 r;
  r.col(0) = f.side;
  r.col(1) = f.pin;
  r.col(2) = f.forward;
  return r;
}

}  // namespace

ToolContactStage::ToolContactStage(const Scene& scene, LameTable lame, ContactOutputs outputs)
    : m_lame(std::move(lame)),
      m_haptic(outputs.haptic_planes),
      m_blade_load(outputs.blade_load || outputs.haptic_planes) {
  for (const Tool& t : scene.tools) {
    m_kinds.push_back(t.kind);
    m_trocars.push_back(t.trocar_m);
  }
  m_tool_force.assign(scene.tools.size(), Vec3::Zero());
  m_planes.resize(scene.tools.size());
  m_near.resize(scene.tools.size());
  m_reactions.resize(scene.tools.size());
}

void ToolContactStage::update_planes(SimState& state) {
  const TetMesh& mesh = state.mesh;
  const SurfaceMesh& s = state.shared.surface;
  if (m_bvh_version != s.topology_version) {
    m_bvh.build(s, mesh.x);
    m_bvh_version = s.topology_version;
  } else {
    m_bvh.refit(mesh.x);
  }
  for (std::size_t i = 0; i < m_kinds.size() && i < state.tools.size(); ++i) {
    m_planes[i].reset();
    m_near[i].reset();
    if (m_kinds[i] == ToolKind::kEndoscope || in_port(state.tools[i])) continue;
    const Vec3 tip = tool_frame(state.tools[i]).tip;
    const std::optional<geometry::ClosestHit> hit = m_bvh.closest_point(mesh.x, tip, kCueRange);
    if (!hit) continue;
    const Tri& f = s.faces[static_cast<std::size_t>(hit->face)];
    const Vec3& a = mesh.x[static_cast<std::size_t>(f[0])];
    const Vec3& b = mesh.x[static_cast<std::size_t>(f[1])];
    const Vec3& c = mesh.x[static_cast<std::size_t>(f[2])];
    const Vec3 n = (b - a).cross(c - a);
    if (!(n.norm() > 0.0)) continue;  // a degenerate face has no plane
    const Vec3 un = n.normalized();
    ContactPlane p;
    p.point_m = {hit->point.x(), hit->point.y(), hit->point.z()};
    p.normal = {un.x(), un.y(), un.z()};
    p.stiffness_Npm = kHapticStiffness;
    m_near[i] = p;
    if (hit->distance <= kHapticRange) m_planes[i] = p;
  }
  state.events.contact_planes = m_planes;
  state.events.tissue_near = m_near;
}

// A scissors stroke begins where the jaws last opened (the widest opening since, kept in the
// grasp's widest_rad) and ends with the cut the cutting stage made of it: its cuts are still in
// the hand-off (the cutting stage runs after this one). The tissue closed on in between resists.
void ToolContactStage::resist_blades(const SimState& state, std::size_t tool, Grasp& g) {
  const ToolState& ts = state.tools[tool];
  const bool cut = std::any_of(state.events.cuts.begin(), state.events.cuts.end(),
                               [&](const CutEvent& c) { return c.tool == tool; });
  if (cut || ts.jaw_rad >= g.widest_rad) g.widest_rad = ts.jaw_rad;
  if (!m_blade_load) return;
  if (m_blades.topology_version() != state.mesh.topology_version ||
      m_blade_nodes != state.mesh.num_nodes()) {
    m_blades.update(state.mesh, m_lame);
    m_blade_nodes = state.mesh.num_nodes();
  }
  const BladeLoad load = m_blades.load(state.mesh, ts, g.widest_rad);
  m_reactions[tool].jaw_torque_nm = load.torque_nm;
  m_reactions[tool].blade_force_n = load.force_n;
}

std::vector<std::size_t> grasped_counts(const SimState& state) {
  std::vector<std::size_t> c(state.tools.size(), 0);
  const auto& grasps = state.blocks.contact.grasps;
  for (std::size_t i = 0; i < grasps.size() && i < c.size(); ++i) c[i] = grasps[i].nodes.size();
  return c;
}

void ToolContactStage::refresh_boundary(const SimState& state) {
  // The surface stage's surface: it runs after this stage, so it is the one of the last step
  // (the assembled state carries the first one), current since no cut comes between.
  const SurfaceMesh& s = state.shared.surface;
  if (m_boundary_version == s.topology_version && m_boundary_nodes == state.mesh.num_nodes())
    return;
  std::vector<std::uint8_t> on(static_cast<std::size_t>(state.mesh.num_nodes()), 0);
  for (const Tri& f : s.faces)
    for (std::int32_t n : f)
      if (n >= 0 && static_cast<std::size_t>(n) < on.size()) on[static_cast<std::size_t>(n)] = 1;
  m_boundary.clear();
  for (std::size_t i = 0; i < on.size(); ++i)
    if (on[i]) m_boundary.push_back(static_cast<std::int32_t>(i));
  m_boundary_version = s.topology_version;
  m_boundary_nodes = state.mesh.num_nodes();
}

namespace {
// The node's own Dirichlet flag, from before the grasp took it (a node it holds).
std::uint8_t flag_of(const ContactBlock::Grasp& g, std::int32_t node) {
  const auto it = std::find(g.nodes.begin(), g.nodes.end(), node);
  return g.was_fixed[static_cast<std::size_t>(it - g.nodes.begin())];
}
}  // namespace

void ToolContactStage::grab(SimState& state, std::size_t tool, Grasp& g) {
  const ToolFrame f = tool_frame(state.tools[tool]);
  const double tan_half = std::tan(0.5 * std::min(g.widest_rad, 3.0));
  const Mat3 rt = frame_matrix(f).transpose();
  g.nodes.clear();
  g.local.clear();
  g.was_fixed.clear();
  for (std::int32_t n : m_boundary) {
    const auto un = static_cast<std::size_t>(n);
    const Vec3 l = rt * (state.mesh.x[un] - f.hinge);  // (side, pin, forward)
    if (l.z() < 0.0 || l.z() > kJawLength) continue;
    if (std::abs(l.y()) > kGraspHalfWidth) continue;
    if (std::abs(l.x()) > l.z() * tan_half + kJawRadius) continue;
    g.nodes.push_back(n);
    g.local.push_back(l);
    const Grasp* other = held_elsewhere(state, n, g);
    g.was_fixed.push_back(other != nullptr ? flag_of(*other, n) : state.mesh.fixed[un]);
  }
  g.holding = true;
}

// Two graspers can hold the same node (one hands tissue to the other): each keeps the node's own
// flag, from before either took it, and only the last to let go gives it back.
const ToolContactStage::Grasp* ToolContactStage::held_elsewhere(const SimState& state,
                                                                std::int32_t node,
                                                                const Grasp& self) {
  for (const Grasp& o : state.blocks.contact.grasps)
    if (&o != &self && o.holding &&
        std::find(o.nodes.begin(), o.nodes.end(), node) != o.nodes.end())
      return &o;
  return nullptr;
}

void ToolContactStage::release(SimState& state, Grasp& g) {
  for (std::size_t k = 0; k < g.nodes.size(); ++k) {
    const auto un = static_cast<std::size_t>(g.nodes[k]);
    if (un < state.mesh.fixed.size() && held_elsewhere(state, g.nodes[k], g) == nullptr)
      state.mesh.fixed[un] = g.was_fixed[k];
  }
  g.nodes.clear();
  g.local.clear();
  g.was_fixed.clear();
  g.holding = false;
  g.widest_rad = 0.0;
}

void ToolContactStage::step(const StepContext& ctx, SimState& state) {
  TetMesh& mesh = state.mesh;
  const auto n = static_cast<std::size_t>(mesh.num_nodes());
  refresh_boundary(state);
  m_force.assign(n, Vec3::Zero());
  m_contacts = 0;
  bool any_force = false;
  state.events.nodes_moved = false;
  auto& grasps = state.blocks.contact.grasps;
  if (grasps.empty()) grasps.resize(m_kinds.size());

  for (std::size_t i = 0; i < m_kinds.size() && i < state.tools.size(); ++i) {
    const ToolState& ts = state.tools[i];
    m_tool_force[i].setZero();
    m_reactions[i] = ToolReaction{};
    if (m_kinds[i] == ToolKind::kEndoscope) continue;
    Grasp& g = grasps[i];
    if (in_port(ts)) {  // withdrawn: it lets go and touches nothing
      withdraw(state, g);
      continue;
    }
    const ToolFrame f = tool_frame(ts);
    if (m_kinds[i] == ToolKind::kScissors) resist_blades(state, i, g);

    // Grasping: grab on closing past the threshold, let go on opening past it.
    if (m_kinds[i] == ToolKind::kGrasper) {
      if (!g.holding) {
        g.widest_rad = std::max(g.widest_rad, ts.jaw_rad);
        if (ts.jaw_rad < kGraspCloseRad && g.widest_rad >= kGraspCloseRad) {
          grab(state, i, g);
          publish_grasps(state);
        }
      } else if (ts.jaw_rad > kGraspCloseRad + kGraspHysteresisRad) {
        release(state, g);
        g.widest_rad = ts.jaw_rad;
        publish_grasps(state);
      }
      if (g.holding && !g.nodes.empty()) {
        // The tissue's pull on the held nodes, measured before they move with the jaws.
        m_flag.assign(n, 0);
        for (std::int32_t k : g.nodes) m_flag[static_cast<std::size_t>(k)] = 1;
        std::vector<Vec3> pull(n, Vec3::Zero());
        add_elastic_forces(mesh, m_lame, m_flag, pull);
        Vec3 total = Vec3::Zero();
        for (std::int32_t k : g.nodes) total += pull[static_cast<std::size_t>(k)];
        m_tool_force[i] = -total;  // the tool pulls against the tissue
        m_reactions[i].held_pull_n = total;
        // Move the held nodes with the jaws (Dirichlet: FEM keeps them where put).
        const Mat3 r = frame_matrix(f);
        for (std::size_t k = 0; k < g.nodes.size(); ++k) {
          const auto un = static_cast<std::size_t>(g.nodes[k]);
          const Vec3 target = f.hinge + r * g.local[k];
          // At rest in the step: FEM evaluates elastic forces at x + (beta + dt) v, so a
          // velocity here would put the held nodes a step ahead of the jaws in the solve (the
          // tissue then overtook the jaws and the grasp force came out reversed).
          mesh.v[un].setZero();
          mesh.x[un] = target;
          mesh.fixed[un] = 1;
        }
        state.events.nodes_moved = true;  // the jaws' work, not the solve's
      }
    }

    // Contact: shaft always; grasper jaws while holding nothing.
    struct Capsule {
      Vec3 a, b;
      double r;
    };
    std::vector<Capsule> caps;
    const Vec3 back = m_trocars[i] ? *m_trocars[i] : Vec3(f.hinge - 0.1 * f.forward);
    caps.push_back({back, f.hinge, kShaftRadius});
    if (m_kinds[i] == ToolKind::kGrasper && !g.holding)
      for (int k = 0; k < 2; ++k) caps.push_back({f.hinge, jaw_tip(f, ts.jaw_rad, k), kJawRadius});
    double shaft_weight = 0.0, shaft_at = 0.0;  // sum |f| and sum |f| * distance from `back`
    for (std::int32_t node : m_boundary) {
      const auto un = static_cast<std::size_t>(node);
      if (mesh.fixed[un] != 0 || !(mesh.mass[un] > 0.0)) continue;
      for (std::size_t ci = 0; ci < caps.size(); ++ci) {
        const Capsule& c = caps[ci];
        const Vec3 q = geometry::closest_point_on_segment(mesh.x[un], c.a, c.b);
        const Vec3 d = mesh.x[un] - q;
        const double dist = d.norm();
        if (dist >= c.r) continue;
        const double depth = c.r - dist;
        const Vec3 dir = dist > 1e-12 ? Vec3(d / dist) : f.pin;
        const double k =
            std::min(kContactStiffness, kContactBeta * mesh.mass[un] / (ctx.dt_s * ctx.dt_s));
        const Vec3 fc = k * depth * dir;
        m_force[un] += fc;
        m_tool_force[i] += fc;
        ++m_contacts;
        any_force = true;
        if (ci == 0) {  // the shaft: what pushes back on it, and where
          m_reactions[i].shaft_push_n -= fc;
          shaft_weight += fc.norm();
          shaft_at += fc.norm() * (q - back).norm();
        }
      }
    }
    // Where along the shaft the push acts, as a fraction of the pivot-to-tip length: at the hand
    // it weighs by that lever about the port (haptics renders it so).
    const double reach = (f.tip - back).norm();
    if (shaft_weight > 0.0 && reach > 0.0)
      m_reactions[i].shaft_lever = std::clamp(shaft_at / shaft_weight / reach, 0.0, 1.0);
  }
  if (m_haptic) update_planes(state);
  if (m_blade_load) state.events.tool_reactions = m_reactions;
  state.events.tool_force_n = m_tool_force;
  if (any_force)
    state.events.external_force_n = m_force;
  else
    state.events.external_force_n.clear();
}

void ToolContactStage::withdraw(SimState& state, Grasp& g) {
  if (g.holding) {
    release(state, g);
    publish_grasps(state);
  }
  g.widest_rad = 0.0;  // inserted again, its jaws must open before they grasp
}

void ToolContactStage::adopt(SimState& state) {
  const auto& grasps = state.blocks.contact.grasps;
  // Every step shapes the block for the scene: a state that has stepped has it so.
  if ((state.step > 0 || !grasps.empty()) && grasps.size() != m_kinds.size())
    throw BlockMismatch("grasps of " + std::to_string(grasps.size()) + " tools, the scene has " +
                        std::to_string(m_kinds.size()));
  for (const Grasp& g : grasps) {
    if (g.local.size() != g.nodes.size() || g.was_fixed.size() != g.nodes.size())
      throw BlockMismatch("a grasp's arrays disagree in size");
    for (std::int32_t n : g.nodes)
      if (n < 0 || n >= state.mesh.num_nodes())
        throw BlockMismatch("a grasp holds node " + std::to_string(n) + " of " +
                            std::to_string(state.mesh.num_nodes()));
  }
  m_boundary_version = ~0ull;
  m_bvh_version = ~0ull;
  m_blade_nodes = -1;
  publish_grasps(state);
}

void ToolContactStage::publish_grasps(SimState& state) {
  const auto& grasps = state.blocks.contact.grasps;
  state.shared.grasped.resize(grasps.size());
  for (std::size_t i = 0; i < grasps.size(); ++i) state.shared.grasped[i] = grasps[i].nodes;
}

}  // namespace serosa::contact

#include "contact/clip_stage.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

#include "engine/endoloop.h"
#include "engine/geometry/rigid_fit.h"
#include "engine/instrument_hold.h"
#include "engine/sim_state.h"
#include "engine/tool_geometry.h"

namespace serosa::contact {
ClipStage::ClipStage(const Scene& scene) {
  const bool clips = scene.settings.has(Effect::kClips);
  const bool loops = scene.settings.has(Effect::kLoops);
  for (const Tool& t : scene.tools) {
    m_role.push_back(clips && t.kind == ToolKind::kClipApplier ? Role::kApplier
                     : loops && t.kind == ToolKind::kEndoloop  ? Role::kLoop
                     : clips && t.kind == ToolKind::kStapler   ? Role::kStapler
                                                               : Role::kNone);
  }
}

std::int64_t clips_dropped(const SimState& state, std::size_t tool) {
  const auto& d = state.blocks.clips.dropped;
  return tool < d.size() ? d[tool] : 0;
}

std::int64_t stapler_refused(const SimState& state, std::size_t tool) {
  const auto& r = state.blocks.clips.refused;
  return tool < r.size() ? r[tool] : 0;
}

void ClipStage::step(const StepContext& ctx, SimState& state) {
  ClipsBlock& b = state.blocks.clips;
  if (b.widest_rad.empty()) {  // the first step
    b.widest_rad.assign(m_role.size(), 0.0);
    b.dropped.assign(m_role.size(), 0);
    b.refused.assign(m_role.size(), 0);
    b.triggers.assign(m_role.size(), StaplerTrigger{});
  }
  clamp_clones(state);
  if (!state.events.cuts.empty())
    for (Placed& p : state.blocks.clips.placed) prune_anchors(state.mesh, p);
  for (std::size_t i = 0; i < m_role.size() && i < state.tools.size(); ++i) {
    if (m_role[i] == Role::kNone) continue;
    const ToolState& ts = state.tools[i];
    if (in_port(ts)) {  // withdrawn: an open clip, loop or stapler goes out unplaced, unfired
      state.blocks.clips.widest_rad[i] = 0.0;
      state.blocks.clips.triggers[i] = StaplerTrigger{};
      continue;
    }
    if (m_role[i] == Role::kStapler) {
      if (const std::optional<double> fired = state.blocks.clips.triggers[i].update(ts.jaw_rad))
        staple(ctx, state, i, ts, *fired);
      continue;
    }
    const bool loop = m_role[i] == Role::kLoop;
    state.blocks.clips.widest_rad[i] = std::max(state.blocks.clips.widest_rad[i], ts.jaw_rad);
    if (ts.jaw_rad <= (loop ? kLoopCloseRad : kClipCloseRad) &&
        state.blocks.clips.widest_rad[i] >= (loop ? kLoopArmRad : kClipArmRad)) {
      place(ctx, state, i, ts);
      state.blocks.clips.widest_rad[i] =
          ts.jaw_rad;  // the next one needs the jaws (the loop) opened again
    }
  }
  for (Placed& p : state.blocks.clips.placed) {
    const double age = ctx.time_s - p.clip.placed_s;
    carry(p, state, age);
    hold(p, state, age);
  }
  if (!state.blocks.clips.placed.empty())
    state.events.nodes_moved = true;  // the clips' work, not the solve's
  publish(state);
}

void ClipStage::place(const StepContext& ctx, SimState& state, std::size_t tool,
                      const ToolState& ts) {
  Placed p;
  p.clip.tool = tool;
  p.clip.placed_s = ctx.time_s;
  if (m_role[tool] == Role::kLoop)
    cinch(state, tool, ts, p);
  else
    clamp_between_jaws(state, tool, ts, p);
  if (p.nodes.empty()) {
    ++state.blocks.clips.dropped[tool];
    return;
  }
  find_anchors(state.mesh, p);
  state.blocks.clips.placed.push_back(std::move(p));
}

// Jaws closed on a ligature misfire: the staples would meet titanium or suture and the knife
// would cut what holds the tissue. Otherwise each staple line clamps its band; a stapler closed
// on nothing lays none.
void ClipStage::staple(const StepContext& ctx, SimState& state, std::size_t tool,
                       const ToolState& ts, double opening_rad) {
  const StaplerJaws jaws = stapler_jaws(ts, opening_rad);
  const bool on_ligature = std::any_of(
      state.blocks.clips.placed.begin(), state.blocks.clips.placed.end(), [&](const Placed& p) {
        return segment_meets_stapled_region(jaws, p.clip.end(0), p.clip.end(1), p.clip.reach_m());
      });
  if (on_ligature) {
    ++state.blocks.clips.refused[tool];
    return;
  }
  std::array<Placed, 2> lines;
  for (int k = 0; k < 2; ++k) {
    Placed& p = lines[static_cast<std::size_t>(k)];
    p.clip.tool = tool;
    p.clip.placed_s = ctx.time_s;
    clamp_staple_line(state, jaws, k, p);
    // Held from now on: neither line takes the other's nodes as its anchors.
    for (std::int32_t n : p.nodes) state.mesh.fixed[static_cast<std::size_t>(n)] = 1;
  }
  if (lines[0].nodes.empty() && lines[1].nodes.empty()) {
    ++state.blocks.clips.dropped[tool];
    return;
  }
  for (Placed& p : lines) {
    if (p.nodes.empty()) continue;  // tissue on one side of the knife only: one line holds it
    find_anchors(state.mesh, p);
    state.blocks.clips.placed.push_back(std::move(p));
  }
}

void ClipStage::clamp_staple_line(const SimState& state, const StaplerJaws& jaws, int k,
                                  Placed& p) {
  p.clip.kind = Clip::Kind::kStaple;
  p.clip.hinge_m = staple_line_hinge(jaws, k);
  p.clip.frame = jaws.frame;
  const Vec3 centre(0.0, k == 0 ? -kStapleLineOffset : kStapleLineOffset, 0.0);
  const TetMesh& mesh = state.mesh;
  double widest = 0.0;  // the clamped tissue's half thickness across the jaws, m
  for (std::int32_t n = 0; n < mesh.num_nodes(); ++n) {
    const auto un = static_cast<std::size_t>(n);
    if (mesh.fixed[un] != 0) continue;  // the scene's, a grasper's or a ligature's
    const Vec3 l = stapler_local(jaws, mesh.x[un]);
    if (!in_stapled_wedge(jaws, l) || staple_line_of(l) != k) continue;
    p.nodes.push_back(n);
    p.local.push_back(l - centre);
    widest = std::max(widest, std::abs(l.x()));
  }
  p.press = widest > 0.5 * kStapleGap ? 0.5 * kStapleGap / widest : 1.0;
}

void ClipStage::clamp_between_jaws(const SimState& state, std::size_t tool, const ToolState& ts,
                                   Placed& p) const {
  const ToolFrame f = tool_frame(ts);
  p.clip.kind = Clip::Kind::kClip;
  p.clip.hinge_m = f.hinge;
  p.clip.frame.col(0) = f.side;
  p.clip.frame.col(1) = f.pin;
  p.clip.frame.col(2) = f.forward;
  const Mat3 rt = p.clip.frame.transpose();
  const double tan_half = std::tan(0.5 * std::min(state.blocks.clips.widest_rad[tool], 3.0));
  const TetMesh& mesh = state.mesh;
  double widest = 0.0;  // the clamped tissue's half thickness across the clip, m
  for (std::int32_t n = 0; n < mesh.num_nodes(); ++n) {
    const auto un = static_cast<std::size_t>(n);
    if (mesh.fixed[un] != 0) continue;           // the scene's, a grasper's or another clip's
    const Vec3 l = rt * (mesh.x[un] - f.hinge);  // (across, pin, along)
    if (l.z() < kClipStart || l.z() > kClipStart + kClipLength) continue;
    if (std::abs(l.y()) > kClipHalfWidth) continue;
    if (std::abs(l.x()) > l.z() * tan_half) continue;
    p.nodes.push_back(n);
    p.local.push_back(l);
    widest = std::max(widest, std::abs(l.x()));
  }
  p.press = widest > 0.5 * kClipGap ? 0.5 * kClipGap / widest : 1.0;
}

void ClipStage::cinch(const SimState& state, std::size_t tool, const ToolState& ts,
                      Placed& p) const {
  ToolState open = ts;
  open.jaw_rad = state.blocks.clips.widest_rad[tool];  // the ring as it went round the tissue
  const LoopRing ring = loop_ring(open);
  const TetMesh& mesh = state.mesh;
  Vec3 sum = Vec3::Zero();
  for (std::int32_t n = 0; n < mesh.num_nodes(); ++n) {
    const auto un = static_cast<std::size_t>(n);
    if (mesh.fixed[un] != 0) continue;
    const Vec3 d = mesh.x[un] - ring.centre;
    const double axial = d.dot(ring.axis);
    if (std::abs(axial) > kLoopHalfWidth) continue;
    if ((d - axial * ring.axis).norm() > ring.radius_m) continue;
    p.nodes.push_back(n);
    sum += mesh.x[un];
  }
  if (p.nodes.empty()) return;
  // The suture closes round what it holds: centred on it, in the ring's plane.
  const Vec3 mean = sum / static_cast<double>(p.nodes.size());
  const Vec3 u = ring.to_knot.normalized();
  p.clip.kind = Clip::Kind::kLoop;
  p.clip.hinge_m = mean - (mean - ring.centre).dot(ring.axis) * ring.axis;
  p.clip.frame.col(0) = u;
  p.clip.frame.col(1) = ring.axis.cross(u);
  p.clip.frame.col(2) = ring.axis;
  const Mat3 rt = p.clip.frame.transpose();
  double widest = 0.0;  // the farthest ligated node from the axis, m
  for (std::int32_t n : p.nodes) {
    const Vec3 l = rt * (mesh.x[static_cast<std::size_t>(n)] - p.clip.hinge_m);
    p.local.push_back(l);
    widest = std::max(widest, std::hypot(l.x(), l.y()));
  }
  p.press = widest > kLoopTightRadius ? kLoopTightRadius / widest : 1.0;
}

void ClipStage::find_anchors(const TetMesh& mesh, Placed& p) {
  std::vector<std::uint8_t> role(static_cast<std::size_t>(mesh.num_nodes()), 0);  // 1 clamped
  for (std::int32_t n : p.nodes) role[static_cast<std::size_t>(n)] = 1;
  std::vector<int> groups;
  for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
    const Tet& tet = mesh.tets[t];
    if (std::none_of(tet.begin(), tet.end(),
                     [&](std::int32_t n) { return role[static_cast<std::size_t>(n)] == 1; }))
      continue;
    groups.push_back(mesh.group[t]);
    for (std::int32_t n : tet) {
      const auto un = static_cast<std::size_t>(n);
      if (role[un] != 0 || mesh.fixed[un] != 0) continue;
      role[un] = 2;
      p.anchors.push_back(n);
    }
  }
  std::sort(groups.begin(), groups.end());
  groups.erase(std::unique(groups.begin(), groups.end()), groups.end());
  std::sort(p.anchors.begin(), p.anchors.end());
  p.clip.groups = std::move(groups);
  p.clip.nodes = p.nodes.size();
  p.clip.node = p.nodes.front();
  Vec3 rest = Vec3::Zero();
  for (std::int32_t n : p.nodes) rest += mesh.rest[static_cast<std::size_t>(n)];
  p.clip.rest_centre_m = rest / static_cast<double>(p.nodes.size());
}

void ClipStage::prune_anchors(const TetMesh& mesh, Placed& p) {
  std::vector<std::uint8_t> role(static_cast<std::size_t>(mesh.num_nodes()), 0);  // 1 clamped
  for (std::int32_t n : p.nodes) role[static_cast<std::size_t>(n)] = 1;
  for (const Tet& tet : mesh.tets) {
    if (std::none_of(tet.begin(), tet.end(),
                     [&](std::int32_t n) { return role[static_cast<std::size_t>(n)] == 1; }))
      continue;
    for (std::int32_t n : tet)
      if (role[static_cast<std::size_t>(n)] == 0) role[static_cast<std::size_t>(n)] = 2;
  }
  std::size_t kept = 0;
  for (std::size_t k = 0; k < p.anchors.size(); ++k) {
    if (role[static_cast<std::size_t>(p.anchors[k])] != 2) continue;
    p.anchors[kept] = p.anchors[k];
    if (p.settled) p.anchor_ref[kept] = p.anchor_ref[k];
    ++kept;
  }
  p.anchors.resize(kept);
  if (p.settled) p.anchor_ref.resize(kept);
}

// A cut of the last step may have cloned a clamped node (the clone takes the tets on one side):
// it is held where its original is.
void ClipStage::clamp_clones(SimState& state) {
  if (state.events.cuts.empty() || state.blocks.clips.placed.empty()) return;
  std::int64_t added = 0;
  for (const CutEvent& c : state.events.cuts)
    added += static_cast<std::int64_t>(c.delta.added_nodes.size());
  std::int64_t first_new = state.mesh.num_nodes() - added;  // id of the first cut's first node
  for (const CutEvent& c : state.events.cuts) {
    for (std::size_t k = 0; k < c.delta.added_nodes.size(); ++k) {
      const NodeParent& parent = c.delta.added_nodes[k];
      if (parent.count != 1) continue;
      for (Placed& p : state.blocks.clips.placed) {
        const auto it = std::find(p.nodes.begin(), p.nodes.end(), parent.nodes[0]);
        if (it == p.nodes.end()) continue;
        const Vec3 l = p.local[static_cast<std::size_t>(it - p.nodes.begin())];
        p.nodes.push_back(static_cast<std::int32_t>(first_new + static_cast<std::int64_t>(k)));
        p.local.push_back(l);
        p.clip.nodes = p.nodes.size();
        break;
      }
    }
    first_new += static_cast<std::int64_t>(c.delta.added_nodes.size());
  }
}

void ClipStage::carry(Placed& p, const SimState& state, double age_s) {
  const std::vector<Vec3>& x = state.mesh.x;
  if (age_s < settle_s(p.clip.kind)) return;  // held where it closed while the legs press
  if (!p.settled) {                           // from now on the anchors carry it
    p.anchor_ref.clear();
    for (std::int32_t n : p.anchors) p.anchor_ref.push_back(x[static_cast<std::size_t>(n)]);
    p.ref_hinge = p.clip.hinge_m;
    p.ref_frame = p.clip.frame;
    p.settled = true;
    return;
  }
  if (p.anchors.empty()) return;
  m_to.clear();
  for (std::int32_t n : p.anchors) m_to.push_back(x[static_cast<std::size_t>(n)]);
  const geometry::RigidMotion m = geometry::fit_rigid_motion(p.anchor_ref, m_to);
  p.clip.frame = m.rotation * p.ref_frame;
  p.clip.hinge_m = m.rotation * p.ref_hinge + m.translation;
}

void ClipStage::hold(Placed& p, SimState& state, double age_s) const {
  TetMesh& mesh = state.mesh;
  const double scale = 1.0 + (p.press - 1.0) * std::clamp(age_s / squeeze_s(p.clip.kind), 0.0, 1.0);
  for (std::size_t k = 0; k < p.nodes.size(); ++k) {
    const auto un = static_cast<std::size_t>(p.nodes[k]);
    if (un >= mesh.x.size()) continue;
    const bool loop = p.clip.kind == Clip::Kind::kLoop;  // a loop presses radially
    const Vec3 l(p.local[k].x() * scale, p.local[k].y() * (loop ? scale : 1.0), p.local[k].z());
    mesh.x[un] = p.clip.hinge_m + p.clip.frame * l;
    mesh.v[un].setZero();  // at rest in the step, as a grasper's held nodes
    mesh.fixed[un] = 1;
  }
}

void ClipStage::publish(SimState& state) const {
  state.shared.clips.resize(state.blocks.clips.placed.size());
  for (std::size_t i = 0; i < state.blocks.clips.placed.size(); ++i)
    state.shared.clips[i] = state.blocks.clips.placed[i].clip;
}

void ClipStage::adopt(SimState& state) {
  const ClipsBlock& b = state.blocks.clips;
  const std::size_t tools = m_role.size();
  for (std::size_t size :
       {b.widest_rad.size(), b.dropped.size(), b.refused.size(), b.triggers.size()})
    if ((state.step > 0 || size != 0) && size != tools)  // (the first step shapes them)
      throw BlockMismatch("ligatures of " + std::to_string(size) + " tools, the scene has " +
                          std::to_string(tools));
  for (const Placed& p : b.placed) {
    if (p.clip.kind > Clip::Kind::kStaple) throw BlockMismatch("an unknown kind of ligature");
    if (p.local.size() != p.nodes.size() ||
        (p.settled && p.anchor_ref.size() != p.anchors.size()) || p.clip.tool >= tools)
      throw BlockMismatch("a clip's arrays disagree in size");
    for (const std::vector<std::int32_t>* ids : {&p.nodes, &p.anchors})
      for (std::int32_t n : *ids)
        if (n < 0 || n >= state.mesh.num_nodes())
          throw BlockMismatch("a clip holds node " + std::to_string(n) + " of " +
                              std::to_string(state.mesh.num_nodes()));
    if (p.nodes.empty()) throw BlockMismatch("a clip clamps no node");
  }
  publish(state);
}

}  // namespace serosa::contact

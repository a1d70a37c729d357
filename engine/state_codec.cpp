#include "engine/state_codec.h"

#include <stdexcept>

#include "engine/input_error.h"

namespace serosa {

void StateWriter::raw(const void* p, std::size_t n) {
  const auto* c = static_cast<const std::uint8_t*>(p);
  m_out.insert(m_out.end(), c, c + n);
}

void StateWriter::string(const std::string& s) {
  u32(static_cast<std::uint32_t>(s.size()));
  raw(s.data(), s.size());
}

// Field by field: a ToolState has padding, whose bytes copies need not keep.
void StateWriter::tool_state(const ToolState& t) {
  u64(t.tick);
  f64(t.time_s);
  for (double c : t.tip_m) f64(c);
  for (double c : t.quat_wxyz) f64(c);
  f64(t.jaw_rad);
  u32(t.buttons);
}

void StateReader::fail(const std::string& message) const {
  throw InputError(m_what, 0, "byte " + std::to_string(m_pos) + ": " + message);
}

void StateReader::raw(void* p, std::size_t n) {
  if (n > left()) fail("snapshot ends early (" + std::to_string(n) + " bytes wanted)");
  if (n > 0) std::memcpy(p, m_in.data() + m_pos, n);
  m_pos += n;
}

std::span<const std::uint8_t> StateReader::view(std::size_t n) {
  if (n > left()) fail("snapshot ends early (" + std::to_string(n) + " bytes wanted)");
  const auto v = m_in.subspan(m_pos, n);
  m_pos += n;
  return v;
}

std::uint8_t StateReader::u8() {
  std::uint8_t v = 0;
  raw(&v, 1);
  return v;
}
std::uint32_t StateReader::u32() {
  std::uint32_t v = 0;
  raw(&v, sizeof v);
  return v;
}
std::uint64_t StateReader::u64() {
  std::uint64_t v = 0;
  raw(&v, sizeof v);
  return v;
}
double StateReader::f64() {
  double v = 0;
  raw(&v, sizeof v);
  return v;
}
std::string StateReader::string() {
  const std::uint32_t n = u32();
  const auto v = view(n);
  return {v.begin(), v.end()};
}

ToolState StateReader::tool_state() {
  ToolState t;
  t.tick = u64();
  t.time_s = f64();
  for (double& c : t.tip_m) c = f64();
  for (double& c : t.quat_wxyz) c = f64();
  t.jaw_rad = f64();
  t.buttons = u32();
  return t;
}

namespace {

void write_mesh(StateWriter& out, const TetMesh& m) {
  out.array(m.rest);
  out.array(m.x);
  out.array(m.v);
  out.array(m.mass);
  out.array(m.fixed);
  out.array(m.tets);
  out.array(m.group);
  out.u64(m.topology_version);
}

void read_mesh(StateReader& in, TetMesh& m) {
  in.array(m.rest);
  in.array(m.x);
  in.array(m.v);
  in.array(m.mass);
  in.array(m.fixed);
  in.array(m.tets);
  in.array(m.group);
  m.topology_version = in.u64();
  const std::size_t n = m.rest.size();
  if (m.x.size() != n || m.v.size() != n || m.mass.size() != n || m.fixed.size() != n ||
      m.group.size() != m.tets.size())
    in.fail("the mesh's arrays disagree in size");
  for (const Tet& t : m.tets)
    for (std::int32_t i : t)
      if (i < 0 || static_cast<std::size_t>(i) >= n) in.fail("a tet names a node out of range");
}

void write_surface(StateWriter& out, const SurfaceMesh& s) {
  out.array(s.faces);
  out.array(s.face_tet);
  out.array(s.face_group);
  out.array(s.face_cut);
  out.u64(s.groups.size());  // field by field: a GroupRange has padding
  for (const GroupRange& g : s.groups) {
    out.u32(g.group);
    out.u32(static_cast<std::uint32_t>(g.offset));
    out.u32(static_cast<std::uint32_t>(g.count));
  }
  out.u64(s.topology_version);
}

void read_surface(StateReader& in, SurfaceMesh& s, std::size_t nodes) {
  in.array(s.faces);
  in.array(s.face_tet);
  in.array(s.face_group);
  in.array(s.face_cut);
  const std::uint64_t groups = in.u64();
  if (groups > in.left() / 12) in.fail("too many face groups");
  s.groups.resize(static_cast<std::size_t>(groups));
  for (GroupRange& g : s.groups) {
    g.group = static_cast<std::uint16_t>(in.u32());
    g.offset = static_cast<std::int32_t>(in.u32());
    g.count = static_cast<std::int32_t>(in.u32());
  }
  s.topology_version = in.u64();
  const std::size_t f = s.faces.size();
  if (s.face_tet.size() != f || s.face_group.size() != f || s.face_cut.size() != f)
    in.fail("the surface's arrays disagree in size");
  for (const Tri& t : s.faces)
    for (std::int32_t i : t)
      if (i < 0 || static_cast<std::size_t>(i) >= nodes)
        in.fail("a face names a node out of range");
}

}  // namespace

void write_sim_state(StateWriter& out, const SimState& s) {
  if (!s.events.cuts.empty())
    throw std::logic_error("write_sim_state: a step's cuts are still in flight");
  out.f64(s.time_s);
  out.u64(s.step);
  write_mesh(out, s.mesh);
  out.u32(static_cast<std::uint32_t>(s.tools.size()));
  for (const ToolState& t : s.tools) out.tool_state(t);
  out.array(s.events.external_force_n);
  out.u8(s.events.nodes_moved ? 1 : 0);
  out.array(s.events.tool_force_n);
  write_surface(out, s.shared.surface);
}

SimState read_sim_state(StateReader& in) {
  SimState s;
  s.time_s = in.f64();
  s.step = in.u64();
  read_mesh(in, s.mesh);
  const std::uint32_t tools = in.u32();
  if (tools > in.left()) in.fail("too many tools");
  for (std::uint32_t i = 0; i < tools; ++i) s.tools.push_back(in.tool_state());
  in.array(s.events.external_force_n);
  s.events.nodes_moved = in.u8() != 0;
  in.array(s.events.tool_force_n);
  read_surface(in, s.shared.surface, s.mesh.rest.size());
  if (!s.events.external_force_n.empty() && s.events.external_force_n.size() != s.mesh.rest.size())
    in.fail("external forces for " + std::to_string(s.events.external_force_n.size()) +
            " nodes, the mesh has " + std::to_string(s.mesh.rest.size()));
  return s;
}

}  // namespace serosa

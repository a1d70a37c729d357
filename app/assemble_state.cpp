#include "app/assemble_state.h"

#include <algorithm>
#include <set>

#include "engine/input_error.h"
#include "surface/extract_surface.h"

namespace serosa::app {

std::map<int, std::string> AssembledScene::group_names() const {
  std::map<int, std::string> names;
  for (const auto& [id, info] : groups) names[id] = info.name;
  return names;
}

const Material& AssembledScene::material(const Scene& scene, int g) const {
  const GroupInfo& info = groups.at(g);
  return scene.organs[info.organ].material_for(info.local_id);
}

namespace {

// Marks the nodes the organ's fixed selections pick (box in the scene frame, groups, node ids in
// mesh-file order) and counts what each picked.
FixedCount fix_nodes(const Scene& scene, const Organ& organ, const TetMesh& part,
                     std::int32_t node_base, const std::map<int, int>& to_global, TetMesh& mesh) {
  const FixedSpec& fixed = organ.fixed;
  FixedCount count{organ.name, {}, {}, {}, 0};
  std::vector<std::uint8_t> picked(static_cast<std::size_t>(part.num_nodes()), 0);
  if (fixed.box) {
    count.box = 0;
    for (std::int32_t i = 0; i < part.num_nodes(); ++i)
      if (fixed.box->contains(mesh.rest[node_base + i])) {
        picked[static_cast<std::size_t>(i)] = 1;
        ++*count.box;
      }
  }
  if (!fixed.groups.empty()) {
    std::vector<std::uint8_t> in_groups(picked.size(), 0);
    for (int g : fixed.groups) {
      if (!to_global.count(g))
        throw InputError(scene.file.string(), 0,
                         "organ '" + organ.name + "': fixed group " + std::to_string(g) +
                             " has no tets in " + organ.mesh.string(),
                         "one of the mesh's group ids");
      for (std::int32_t t = 0; t < part.num_tets(); ++t)
        if (part.group[t] == g)
          for (std::int32_t id : part.tets[t]) in_groups[static_cast<std::size_t>(id)] = 1;
    }
    count.groups = 0;
    for (std::size_t i = 0; i < picked.size(); ++i)
      if (in_groups[i]) {
        picked[i] = 1;
        ++*count.groups;
      }
  }
  if (!fixed.nodes.empty()) count.nodes = static_cast<std::int32_t>(fixed.nodes.size());
  for (std::int32_t id : fixed.nodes) {
    if (id < 0 || id >= part.num_nodes())
      throw InputError(
          scene.file.string(), 0,
          "organ '" + organ.name + "': fixed node " + std::to_string(id) + " out of range",
          "0.." + std::to_string(part.num_nodes() - 1));
    picked[static_cast<std::size_t>(id)] = 1;
  }
  for (std::size_t i = 0; i < picked.size(); ++i)
    if (picked[i]) {
      mesh.fixed[static_cast<std::size_t>(node_base) + i] = 1;
      ++count.total;
    }
  return count;
}

}  // namespace

AssembledScene assemble_state(const Scene& scene) {
  AssembledScene out;
  TetMesh& mesh = out.state.mesh;
  int group_offset = 0;
  for (std::size_t k = 0; k < scene.organs.size(); ++k) {
    const Organ& organ = scene.organs[k];
    MeshReadReport report;
    const TetMesh part = read_mesh(organ.mesh, {}, &report);
    const std::int32_t node_base = mesh.num_nodes();

    // Nodes, placed in the scene frame.
    for (std::int32_t i = 0; i < part.num_nodes(); ++i) {
      const Vec3 p = organ.transform.apply(part.rest[i]);
      mesh.add_node(p);
    }
    // Groups: scene-wide ids, one organ keeps its own.
    std::set<int> local_groups(part.group.begin(), part.group.end());
    std::map<int, int> to_global;
    for (int local : local_groups) {
      const int global = local + group_offset;
      if (global > 0xFFFF)
        throw InputError(
            scene.file.string(), 0,
            "too many groups across organs (scene-wide group id " + std::to_string(global) + ")",
            "at most 65535");
      to_global[local] = global;
      std::string name = organ.groups.count(local)         ? organ.groups.at(local)
                         : report.group_names.count(local) ? report.group_names.at(local)
                                                           : "group_" + std::to_string(local);
      if (scene.organs.size() > 1) name = organ.name + "/" + name;
      out.groups[global] = {k, local, name};
    }
    for (std::int32_t t = 0; t < part.num_tets(); ++t) {
      Tet tet = part.tets[t];
      for (auto& id : tet) id += node_base;
      mesh.add_tet(tet, static_cast<std::uint16_t>(to_global.at(part.group[t])));
    }
    group_offset = local_groups.empty() ? group_offset : to_global.rbegin()->second;

    out.fixed.push_back(fix_nodes(scene, organ, part, node_base, to_global, mesh));
    out.reads.push_back(std::move(report));
  }
  out.state.tools.resize(scene.tools.size());
  // Until its device first drives it, an instrument waits in its port, out of the tissue (a
  // session's handles drive two instruments; the others are not inside the patient).
  for (std::size_t i = 0; i < scene.tools.size(); ++i)
    if (const auto& port = scene.tools[i].trocar_m)
      out.state.tools[i].tip_m = {port->x(), port->y(), port->z()};
  // The boundary comes with the state: contact, which runs before the surface stage, reads it
  // from the first step on.
  if (scene.settings.has(Effect::kSurface) || scene.settings.has(Effect::kContact))
    out.state.shared.surface = surface::extract_surface(mesh);
  return out;
}

}  // namespace serosa::app

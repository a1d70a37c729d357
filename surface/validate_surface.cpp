#include "surface/validate_surface.h"

#include <cstddef>

#include "surface/face_key.h"

namespace serosa::surface {
namespace {

// True when f is face l of t up to rotation (same orientation) for some l.
bool is_outward_face_of(const Tri& f, const Tet& t) {
  for (int l = 0; l < 4; ++l) {
    Tri g{};
    outward_face(t, l, g[0], g[1], g[2]);
    for (int r = 0; r < 3; ++r)
      if (f[0] == g[r] && f[1] == g[(r + 1) % 3] && f[2] == g[(r + 2) % 3]) return true;
  }
  return false;
}

}  // namespace

std::vector<std::string> validate_surface(const SurfaceMesh& s, const TetMesh& mesh) {
  std::vector<std::string> errs;
  const std::size_t f = s.faces.size();
  if (s.face_tet.size() != f || s.face_group.size() != f || s.face_cut.size() != f) {
    errs.push_back("faces, face_tet, face_group and face_cut differ in size");
    return errs;
  }
  if (s.topology_version != mesh.topology_version)
    errs.push_back("topology_version " + std::to_string(s.topology_version) + " != mesh's " +
                   std::to_string(mesh.topology_version));
  std::int64_t next = 0;
  for (std::size_t g = 0; g < s.groups.size(); ++g) {
    const GroupRange& r = s.groups[g];
    const std::string name = "group " + std::to_string(r.group);
    if (g > 0 && s.groups[g - 1].group >= r.group) errs.push_back(name + " not ascending");
    if (r.count <= 0) errs.push_back(name + " is empty");
    if (r.offset != next) errs.push_back(name + " does not start where the previous one ends");
    next = std::int64_t{r.offset} + r.count;
    if (r.offset < 0 || next > static_cast<std::int64_t>(f)) {
      errs.push_back(name + " out of range");
      return errs;
    }
    for (std::int32_t i = r.offset; i < r.offset + r.count; ++i)
      if (s.face_group[static_cast<std::size_t>(i)] != r.group) {
        errs.push_back("face " + std::to_string(i) + " outside its group's range");
        break;
      }
  }
  if (next != static_cast<std::int64_t>(f)) errs.push_back("group ranges do not cover the faces");
  for (std::size_t i = 0; i < f && errs.size() < 20; ++i) {
    const std::string name = "face " + std::to_string(i);
    const std::int32_t t = s.face_tet[i];
    if (t < 0 || t >= mesh.num_tets()) {
      errs.push_back(name + ": tet " + std::to_string(t) + " does not exist");
      continue;
    }
    if (s.face_cut[i] > 1) errs.push_back(name + ": face_cut is neither 0 nor 1");
    if (mesh.group[static_cast<std::size_t>(t)] != s.face_group[i])
      errs.push_back(name + ": group differs from its tet's");
    for (std::int32_t v : s.faces[i])
      if (v < 0 || v >= mesh.num_nodes()) errs.push_back(name + ": node id out of range");
    if (!is_outward_face_of(s.faces[i], mesh.tets[static_cast<std::size_t>(t)]))
      errs.push_back(name + ": not an outward face of tet " + std::to_string(t));
  }
  return errs;
}

}  // namespace serosa::surface

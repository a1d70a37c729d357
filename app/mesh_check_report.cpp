#include "app/mesh_check_report.h"

#include <system_error>

#include "cutting/validate.h"
#include "engine/input_error.h"

namespace serosa::app {
namespace {

Pieces count_pieces(const TetMesh& mesh, const MeshCheckReport& r) {
  Pieces p;
  for (const auto& [g, tets] : r.group_tets)
    p[g] = cutting::count_components(mesh, static_cast<std::uint16_t>(g));
  return p;
}

}  // namespace

nlohmann::json check_json(const std::string& file, const CheckedMesh& checked) {
  const MeshReadReport& read = checked.read;
  const MeshCheckReport& r = checked.report;
  const Pieces& pieces = checked.pieces;
  nlohmann::json groups = nlohmann::json::array();
  for (const auto& [g, tets] : r.group_tets) {
    nlohmann::json j{{"id", g}, {"tets", tets}, {"volume_m3", 0.0}, {"pieces", pieces.at(g)}};
    if (const auto v = r.group_volume_m3.find(g); v != r.group_volume_m3.end()) {
      j["volume_m3"] = v->second;
    }
    if (const auto n = read.group_names.find(g); n != read.group_names.end()) j["name"] = n->second;
    groups.push_back(std::move(j));
  }
  return {
      {"file", file},
      {"format", read.format},
      {"nodes", r.nodes},
      {"tets", r.tets},
      {"volume_m3", r.volume_m3},
      {"groups", groups},
      {"bbox_min_m", {r.bbox_min.x(), r.bbox_min.y(), r.bbox_min.z()}},
      {"bbox_max_m", {r.bbox_max.x(), r.bbox_max.y(), r.bbox_max.z()}},
      {"quality_measure", "mean_ratio"},
      {"min_quality", r.min_quality},
      {"median_quality", r.median_quality},
      {"inverted_tets", r.inverted_tets},
      {"flat_tets", r.flat_tets},
      {"duplicate_tets", r.duplicate_tets},
      {"bad_tets", r.bad_tets},
      {"boundary_faces", r.boundary_faces},
      {"interior_faces", r.interior_faces},
      {"overshared_faces", r.overshared_faces},
      {"misoriented_faces", r.misoriented_faces},
      {"unreferenced_nodes", r.unreferenced_nodes},
      {"nonfinite_nodes", r.nonfinite_nodes},
      {"skipped_elements", read.skipped_elements},
      {"repaired_inverted", read.repaired_inverted},
      {"valid", r.valid},
      {"problems", r.problems},
      {"warnings", r.warnings},
  };
}

CheckedMesh check_mesh_file(const std::filesystem::path& path, bool repair_inverted) {
  // The reader names a missing file too, but say it here plainly whatever the reader does.
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) {
    throw InputError(path.string(), 0, "no such file", "an existing mesh file");
  }
  if (std::filesystem::is_directory(path, ec)) {
    throw InputError(path.string(), 0, "is a directory", "a mesh file");
  }
  MeshReadOptions options;
  options.repair_inverted = repair_inverted;
  CheckedMesh c;
  c.mesh = read_mesh(path, options, &c.read);
  MeshCheckOptions check_options;
  check_options.flat_tolerance = options.flat_tolerance;
  check_options.tet_lines = c.read.tet_lines;  // a problem names the tet's element and line
  check_options.tet_ids = c.read.tet_ids;
  check_options.tet_file = c.read.tet_file;
  c.report = check_mesh(c.mesh, check_options);
  c.pieces = count_pieces(c.mesh, c.report);
  return c;
}

}  // namespace serosa::app

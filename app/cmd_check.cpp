// serosa check MESH [--json] [--repair-inverted]: load and validate a mesh; print counts, volume
// and pieces per group, quality, inverted/flat tets, overshared and boundary faces
// (docs/ARCHITECTURE.md "External contracts"). Exit 0 on a valid mesh, 1 on bad input (the reader's
// InputError, printed by main.cpp with file and line) or on a mesh that parses but is invalid
// (problems printed).
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "app/command.h"
#include "app/mesh_check_report.h"
#include "engine/input_error.h"
#include "engine/io/mesh_io.h"
#include "engine/mesh_check.h"

namespace serosa::app {

namespace {

struct CheckArgs {
  std::string mesh;              // path of the mesh file
  bool json = false;             // one JSON object on stdout instead of text
  bool repair_inverted = false;  // let the reader fix inverted tets instead of rejecting them
};

std::string group_label(int g, const MeshReadReport& read) {
  const auto it = read.group_names.find(g);
  return it == read.group_names.end() ? std::to_string(g)
                                      : std::to_string(g) + " (" + it->second + ")";
}

void print_text(const std::string& file, const MeshReadReport& read, const MeshCheckReport& r,
                const Pieces& pieces) {
  std::printf("mesh        %s (%s)\n", file.c_str(), read.format.c_str());
  std::printf("nodes       %lld\n", static_cast<long long>(r.nodes));
  std::printf("tets        %lld\n", static_cast<long long>(r.tets));
  std::printf("volume      %.6g m^3\n", r.volume_m3);
  for (const auto& [g, tets] : r.group_tets) {
    const auto v = r.group_volume_m3.find(g);
    const std::int32_t n = pieces.at(g);
    std::printf("  group %-16s %lld tets, %.6g m^3, %d piece%s\n", group_label(g, read).c_str(),
                static_cast<long long>(tets), v == r.group_volume_m3.end() ? 0.0 : v->second, n,
                n == 1 ? "" : "s");
  }
  std::printf("bbox        [%.6g, %.6g, %.6g] .. [%.6g, %.6g, %.6g] m\n", r.bbox_min.x(),
              r.bbox_min.y(), r.bbox_min.z(), r.bbox_max.x(), r.bbox_max.y(), r.bbox_max.z());
  std::printf("quality     min %.4g, median %.4g (mean ratio; 1 = regular, <= 0 = flat/inverted)\n",
              r.min_quality, r.median_quality);
  std::printf("inverted    %lld tets\n", static_cast<long long>(r.inverted_tets));
  std::printf("flat        %lld tets\n", static_cast<long long>(r.flat_tets));
  std::printf("faces       %lld boundary, %lld interior, %lld overshared (> 2 tets)\n",
              static_cast<long long>(r.boundary_faces), static_cast<long long>(r.interior_faces),
              static_cast<long long>(r.overshared_faces));
  if (read.skipped_elements > 0) {
    std::printf("skipped     %lld non-tet elements\n",
                static_cast<long long>(read.skipped_elements));
  }
  if (read.repaired_inverted > 0) {
    std::printf("repaired    %lld inverted tets (node order swapped)\n",
                static_cast<long long>(read.repaired_inverted));
  }
  for (const auto& w : r.warnings) std::printf("warning     %s\n", w.c_str());
  std::printf("%s\n", r.valid ? "valid" : "INVALID");
}

int run_check(const CheckArgs& args) {
  const CheckedMesh checked = check_mesh_file(args.mesh, args.repair_inverted);
  const MeshCheckReport& report = checked.report;
  const MeshReadReport& read = checked.read;
  const Pieces& pieces = checked.pieces;
  if (args.json) {
    std::printf("%s\n", check_json(args.mesh, checked).dump(2).c_str());
  } else {
    print_text(args.mesh, read, report, pieces);
  }
  if (!report.valid) {
    for (const auto& p : report.problems) {
      std::fprintf(stderr, "error: %s: %s\n", args.mesh.c_str(), p.c_str());
    }
    return 1;
  }
  return 0;
}

// With --json, a mesh that does not load is a JSON error object on stdout too (exit 1), so a
// script reading stdout never gets nothing.
int run_check_reporting(const CheckArgs& args) {
  if (!args.json) return run_check(args);
  try {
    return run_check(args);
  } catch (const InputError& e) {
    const nlohmann::json j{{"mesh", args.mesh},
                           {"valid", false},
                           {"error",
                            {{"file", e.file()},
                             {"line", e.line()},
                             {"message", e.message()},
                             {"expected", e.expected()}}}};
    std::printf("%s\n", j.dump(2).c_str());
    throw;  // and on stderr as every other error
  }
}

}  // namespace

void add_check_command(CLI::App& app, Action& action) {
  auto args = std::make_shared<CheckArgs>();
  CLI::App* cmd = app.add_subcommand("check", "Load and validate a tet mesh; print its statistics");
  cmd->add_option("mesh", args->mesh, "Mesh file (.msh Gmsh 2.2/4.1, .node/.ele TetGen, .vtk)")
      ->required();
  cmd->add_flag("--json", args->json, "Print one JSON object instead of text");
  cmd->add_flag("--repair-inverted", args->repair_inverted,
                "Repair inverted tets (swap two nodes) instead of rejecting the file");
  cmd->callback([&action, args] { action = [args] { return run_check_reporting(*args); }; });
}

}  // namespace serosa::app

// serosa cut MESH --polygon "x,y,z x,y,z x,y,z[ ...]" [--polygon ...] --out OUT.msh
//            [--method pattern|remove|snap] [--stroke] [--json]
// Applies each convex planar polygon in turn (world coordinates, m) with the chosen method
// (cutting/cut_method.h); with --stroke (pattern method) the polygons are the steps of one
// progressive stroke (cutting/progressive_cut.h: consecutive coplanar polygons whose union is
// convex are cut as the region swept so far; the nodes in no tet, which each step releases, are
// dropped from the output, and a stroke's "tets created" are its pieces at its end). Writes the
// result at rest positions in the format --out's name says: .msh (Gmsh 2.2 ASCII, each tet's group
// as its physical tag), .vtu (ParaView) or .obj (the boundary surface); and prints a
// summary: tets, nodes, volume and minimum quality before and after, tets created, and the time of
// each cut (docs/ARCHITECTURE.md "External contracts"). A cut's time is the candidate query through
// the BVH, the cut itself, apply() and the BVH's local update. Bad flags (a polygon that does not
// parse, has fewer than 3 points, is not planar or not convex; an unknown method; an --out that is
// a folder, lies in no existing folder or names no format) are InputErrors naming the flag and its
// value: exit 1, before any cut runs. A polygon that changes nothing is a warning (stderr, and the
// JSON's "warnings"). Debug builds check every pattern cut with cutting::check_cut (a broken
// invariant is our bug: exit 2).
#include <charconv>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "app/command.h"
#include "app/output_paths.h"
#include "cutting/convex_polygon.h"
#include "cutting/cut_method.h"
#include "cutting/progressive_cut.h"
#include "cutting/reserve.h"
#include "cutting/tet_bvh.h"
#include "cutting/validate.h"
#include "engine/input_error.h"
#include "engine/io/mesh_io.h"
#include "engine/mesh_check.h"
#include "engine/topology_delta.h"

namespace serosa::app {

namespace {

constexpr const char* kPolygonForm =
    "\"x,y,z x,y,z x,y,z[ ...]\": at least 3 points in metres, planar and convex";

struct CutArgs {
  std::string mesh;                   // input mesh file
  std::vector<std::string> polygons;  // one --polygon value each, applied in order
  std::string out;                    // output .msh (Gmsh 2.2 ASCII)
  std::string method = "pattern";     // pattern | remove | snap
  bool stroke = false;                // the polygons are one progressive stroke (pattern only)
  bool json = false;                  // one JSON object on stdout instead of text
};

// "--polygon #k "VALUE"" as the InputError's "file" (it names the flag and its value).
std::string polygon_where(std::size_t k, const std::string& value) {
  std::string s = "--polygon #";
  s.append(std::to_string(k + 1)).append(" \"").append(value).append("\"");
  return s;
}

// Parses one --polygon value into a validated ConvexPolygon.
cutting::ConvexPolygon parse_polygon(std::size_t k, const std::string& value) {
  const std::string where = polygon_where(k, value);
  std::vector<Vec3> pts;
  std::istringstream in(value);
  std::string token;
  while (in >> token) {
    Vec3 p;
    std::size_t start = 0;
    for (int c = 0; c < 3; ++c) {
      const std::size_t comma = token.find(',', start);
      const bool last = c == 2;
      if (last != (comma == std::string::npos)) {
        std::string msg = "point ";
        msg.append(std::to_string(pts.size() + 1)).append(" \"").append(token);
        msg.append("\" does not have exactly three comma-separated coordinates");
        throw InputError(where, 0, msg, kPolygonForm);
      }
      const std::string num = token.substr(start, last ? std::string::npos : comma - start);
      double v = 0.0;
      const auto [ptr, ec] = std::from_chars(num.data(), num.data() + num.size(), v);
      if (ec != std::errc() || ptr != num.data() + num.size() || num.empty() || !std::isfinite(v)) {
        std::string msg = "point ";
        msg.append(std::to_string(pts.size() + 1)).append(" \"").append(token);
        msg.append("\": \"").append(num).append("\" is not a finite number");
        throw InputError(where, 0, msg, kPolygonForm);
      }
      p[c] = v;
      start = comma + 1;
    }
    pts.push_back(p);
  }
  if (pts.size() < 3) {
    std::string msg = "has ";
    msg.append(std::to_string(pts.size())).append(" point(s)");
    throw InputError(where, 0, msg, kPolygonForm);
  }
  std::string why;
  auto poly = cutting::ConvexPolygon::make(std::move(pts), 1e-6, &why);
  if (!poly) throw InputError(where, 0, "not a valid blade polygon: " + why, kPolygonForm);
  return *poly;
}

struct MeshSummary {
  std::int64_t tets = 0, nodes = 0;
  double volume_m3 = 0.0, min_quality = 0.0;
};

MeshSummary summarize(const TetMesh& mesh) {
  const MeshCheckReport r = check_mesh(mesh);
  return {r.tets, r.nodes, r.volume_m3, r.min_quality};
}

nlohmann::json to_json(const MeshSummary& s) {
  return {{"tets", s.tets},
          {"nodes", s.nodes},
          {"volume_m3", s.volume_m3},
          {"min_quality", s.min_quality}};
}

// Drops the nodes no tet uses (a progressive stroke's released nodes, and any the input had),
// keeping the others' order.
void drop_unused_nodes(TetMesh& mesh) {
  mesh.fill_node_state();
  std::vector<std::int32_t> id(static_cast<std::size_t>(mesh.num_nodes()), -1);
  for (const Tet& t : mesh.tets)
    for (std::int32_t v : t) id[static_cast<std::size_t>(v)] = 0;
  std::int32_t next = 0;
  for (std::size_t i = 0; i < id.size(); ++i) {
    if (id[i] < 0) continue;
    id[i] = next;
    const auto to = static_cast<std::size_t>(next++);
    mesh.rest[to] = mesh.rest[i];
    mesh.x[to] = mesh.x[i];
    mesh.v[to] = mesh.v[i];
    mesh.mass[to] = mesh.mass[i];
    mesh.fixed[to] = mesh.fixed[i];
  }
  const auto n = static_cast<std::size_t>(next);
  mesh.rest.resize(n);
  mesh.x.resize(n);
  mesh.v.resize(n);
  mesh.mass.resize(n);
  mesh.fixed.resize(n);
  for (Tet& t : mesh.tets)
    for (std::int32_t& v : t) v = id[static_cast<std::size_t>(v)];
  ++mesh.topology_version;
}

int run_cut(const CutArgs& args) {
  const auto method = cutting::parse_cut_method(args.method);
  if (!method) {
    std::string where = "--method \"";
    where.append(args.method).append("\"");
    throw InputError(where, 0, "unknown cut method", "pattern, remove or snap");
  }
  if (args.stroke && *method != cutting::CutMethod::kPattern) {
    std::string where = "--stroke with --method \"";
    where.append(args.method).append("\"");
    throw InputError(where, 0, "a progressive stroke re-cuts with the pattern method only",
                     "--method pattern (the default)");
  }
  std::vector<cutting::ConvexPolygon> blades;
  for (std::size_t k = 0; k < args.polygons.size(); ++k)
    blades.push_back(parse_polygon(k, args.polygons[k]));
  std::error_code ec;
  if (!std::filesystem::exists(args.mesh, ec))
    throw InputError(args.mesh, 0, "no such file", "an existing mesh file");

  // The output's place is checked before any cut runs (a long run must not end on a typo).
  check_output_file("--out", args.out);
  const MeshOutputFormat format = mesh_output_format("--out", args.out);

  MeshReadReport read;
  TetMesh mesh = read_mesh(args.mesh, {}, &read);
  const MeshSummary before = summarize(mesh);
  cutting::reserve_for_cuts(mesh);  // spare capacity: no cut reallocates the per-tet arrays
  cutting::TetBvh bvh(mesh);        // (the BVH reserves its own)
  cutting::ProgressiveCut stroke;

  // Each cut: candidates through the BVH, the cut, apply(), the BVH's local update.
  nlohmann::json cuts = nlohmann::json::array();
  nlohmann::json warnings = nlohmann::json::array();
  std::int64_t created = 0;
  double total_ms = 0.0;
  for (std::size_t k = 0; k < blades.size(); ++k) {
    cutting::reserve_for_cuts(mesh);  // O(1) unless the spare ran low (untimed)
#ifndef NDEBUG
    // Debug builds check every single cut with the invariant checker (cutting/validate.h).
    std::optional<TetMesh> unchecked;
    if (!args.stroke && *method == cutting::CutMethod::kPattern) unchecked = mesh;
#endif
    const auto t0 = std::chrono::steady_clock::now();
    // A stroke's tets created are its pieces when it ends (one cut of its region), not the sum
    // of the steps' deltas, which re-add the pieces every step.
    const auto pieces_before = static_cast<std::int64_t>(stroke.num_pieces());
    cutting::CutResult r = args.stroke
                               ? stroke.cut(mesh, blades[k], bvh.as_query())
                               : cutting::cut_with(*method, mesh, blades[k], {}, bvh.as_query());
    apply(mesh, r.delta);
    if (args.stroke) stroke.applied(mesh, r.delta);
    bvh.update(mesh, r.delta);
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
#ifndef NDEBUG
    if (unchecked) {  // untimed
      cutting::CutCheckOptions co;
      co.geometry_tol_m = 4.0 * r.stats.tolerance_m + 1e-12;
      co.plane_tol_m = r.stats.tolerance_m;
      const cutting::CutCheckReport check = cutting::check_cut(*unchecked, mesh, blades[k], co);
      if (!check.ok)
        throw std::logic_error("cut " + std::to_string(k + 1) +
                               " broke an invariant: " + check.problems.front());
    }
#endif
    total_ms += ms;
    // The delta's own sizes: a stroke step also removes the previous step's pieces.
    const auto removed = static_cast<std::int64_t>(r.delta.removed_tets.size());
    const auto added = static_cast<std::int64_t>(r.delta.added_tets.size());
    if (!args.stroke) created += added;
    nlohmann::json c{{"polygon", k + 1},
                     {"time_ms", ms},
                     {"candidates", r.stats.candidates},
                     {"tets_removed", removed},
                     {"tets_added", added},
                     {"nodes_added", static_cast<std::int64_t>(r.delta.added_nodes.size())}};
    if (args.stroke) {
      if (!stroke.last_step().extended) created += pieces_before;  // the previous stroke ended
      c["extends_stroke"] = stroke.last_step().extended;
      c["nodes_released"] = stroke.last_step().nodes_released;
    }
    cuts.push_back(std::move(c));
    // A polygon that changes nothing is almost always a mistake in its coordinates: said, not
    // silent (the output is still written).
    if (r.delta.empty()) {
      std::string w = "polygon " + std::to_string(k + 1) + " changed nothing: ";
      w.append(r.stats.candidates == 0 ? "its bounding box meets no tet of the mesh"
                                       : "it crosses no tet of the mesh");
      warnings.push_back(w);
      if (!args.json) std::fprintf(stderr, "warning: %s\n", w.c_str());
    }
  }
  if (args.stroke) {
    created += static_cast<std::int64_t>(stroke.num_pieces());
    drop_unused_nodes(mesh);
  }
  write_mesh_output(args.out, format, mesh, read.group_names, /*current=*/false);
  const MeshSummary after = summarize(mesh);

  if (args.json) {
    const nlohmann::json j{{"mesh", args.mesh},
                           {"out", args.out},
                           {"method", std::string(cutting::to_string(*method))},
                           {"stroke", args.stroke},
                           {"quality_measure", "mean_ratio"},
                           {"before", to_json(before)},
                           {"after", to_json(after)},
                           {"tets_created", created},
                           {"total_time_ms", total_ms},
                           {"cuts", cuts},
                           {"warnings", warnings}};
    std::printf("%s\n", j.dump(2).c_str());
  } else {
    std::printf("cut %s with %zu polygon(s), method %s -> %s\n", args.mesh.c_str(), blades.size(),
                std::string(cutting::to_string(*method)).c_str(), args.out.c_str());
    std::printf("tets        %lld -> %lld (%lld created)\n", static_cast<long long>(before.tets),
                static_cast<long long>(after.tets), static_cast<long long>(created));
    std::printf("nodes       %lld -> %lld\n", static_cast<long long>(before.nodes),
                static_cast<long long>(after.nodes));
    std::printf("volume      %.9g -> %.9g m^3\n", before.volume_m3, after.volume_m3);
    std::printf("min quality %.4g -> %.4g (mean ratio)\n", before.min_quality, after.min_quality);
    for (const auto& c : cuts)
      std::printf("cut %d      %.3f ms, %lld tets removed, %lld added\n", c["polygon"].get<int>(),
                  c["time_ms"].get<double>(), c["tets_removed"].get<long long>(),
                  c["tets_added"].get<long long>());
  }
  return 0;
}

}  // namespace

void add_cut_command(CLI::App& app, Action& action) {
  auto args = std::make_shared<CutArgs>();
  CLI::App* cmd = app.add_subcommand(
      "cut", "Cut a tet mesh by convex blade polygons; write Gmsh 2.2 and print a summary");
  cmd->add_option("mesh", args->mesh, "Mesh file (.msh Gmsh 2.2/4.1, .node/.ele TetGen, .vtk)")
      ->required();
  cmd->add_option("--polygon", args->polygons,
                  "Blade polygon \"x,y,z x,y,z x,y,z[ ...]\" (m, convex, planar); repeat to cut "
                  "several times, in order")
      ->required()
      ->allow_extra_args(false)
      ->take_all();
  cmd->add_option("--out", args->out, "Output mesh (Gmsh 2.2 ASCII)")->required();
  cmd->add_option("--method", args->method, "pattern (default), remove or snap");
  cmd->add_flag("--stroke", args->stroke,
                "The polygons are the steps of one scissors stroke: coplanar steps whose union is "
                "convex are cut as the region swept so far (pattern method)");
  cmd->add_flag("--json", args->json, "Print one JSON object instead of text");
  cmd->callback([&action, args] { action = [args] { return run_cut(*args); }; });
}

}  // namespace serosa::app

// `serosa bench cutting`: pattern vs element removal vs node snapping (cutting/cut_method.h) over
// the same blade polygons on a generated block of Kuhn tets (engine/kuhn_grid.h), every cut on the
// pristine block. Accuracy (cutting/cut_accuracy.h, the same measurement as bench/cutting
// BM_Method): volume lost, distance of the cut surface from the blade polygon, tets created,
// minimum quality; time: candidate query through the TetBvh + cut + apply + BVH update, ms.
// The pattern method must keep the volume (relative loss <= 1e-12) and put its cut surface on the
// blade's plane: the part throws otherwise.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench/suite/bench_parts.h"
#include "cutting/cut_accuracy.h"
#include "cutting/cut_method.h"
#include "cutting/tet_bvh.h"
#include "engine/kuhn_grid.h"
#include "engine/topology_delta.h"

namespace serosa::bench {
namespace {

using cutting::ConvexPolygon;
using cutting::CutMethod;
using Clock = std::chrono::steady_clock;

constexpr double kH = 0.002;  // cell edge, m (2 mm)

/// A square blade of half-size `half` cells centred at `centre` (cells), plane normal `normal`.
ConvexPolygon blade(const Vec3& centre, double half, const Vec3& normal) {
  const Vec3 n = normal.normalized();
  const Vec3 u = n.cross(Vec3(0.13, 1.0, 0.29)).normalized();
  const Vec3 v = n.cross(u);
  const Vec3 c = centre * kH;
  const double s = half * kH;
  return ConvexPolygon(
      {c - s * u - s * v, c + s * u - s * v, c + s * u + s * v, c - s * u + s * v});
}

struct NamedBlade {
  std::string name;
  ConvexPolygon polygon;
};

/// The blades every method cuts, on the block of n cells: two through the whole block, two that
/// end inside it (a crack front).
std::vector<NamedBlade> blades(int n) {
  const double c = 0.5 * n;
  return {
      {"oblique covering", blade(Vec3(c + 0.1, c + 0.05, c - 0.05), 2.0 * n, Vec3(1, 0.31, 0.17))},
      {"steep covering", blade(Vec3(c - 0.23, c + 0.11, c + 0.07), 2.0 * n, Vec3(0.2, 1, 0.45))},
      {"oblique partial", blade(Vec3(0.155 * n, c + 0.05, c - 0.05), 0.4 * n, Vec3(1, 0.31, 0.17))},
      {"from the top partial", blade(Vec3(c + 0.17, c - 0.09, n), 0.3 * n, Vec3(0.93, -0.21, 0.3))},
  };
}

struct Measured {
  cutting::CutAccuracy accuracy;
  double tets_created = 0.0;
  double ms_per_cut = 0.0;
};

/// One blade, one method: accuracy of one cut of the pristine block, and the fastest of `reps`
/// cuts (each on a fresh copy, reset untimed; the machine may be shared, the minimum is the least
/// disturbed).
Measured measure(const TetMesh& pristine, const cutting::TetBvh& pristine_bvh,
                 const ConvexPolygon& b, CutMethod method, int reps) {
  Measured out;
  TetMesh mesh = pristine;
  cutting::TetBvh bvh = pristine_bvh;
  double seconds = 1e300;
  for (int r = 0; r <= reps; ++r) {  // r = 0: warm-up, also the measured cut
    mesh = pristine;
    bvh = pristine_bvh;
    const auto t0 = Clock::now();
    cutting::CutResult cut = cutting::cut_with(method, mesh, b, {}, bvh.as_query());
    apply(mesh, cut.delta);
    bvh.update(mesh, cut.delta);
    const auto t1 = Clock::now();
    if (r == 0) {
      out.accuracy = cutting::measure_cut(pristine, mesh, b, kH);
      out.tets_created = static_cast<double>(cut.stats.tets_added - cut.stats.tets_removed);
    } else {
      seconds = std::min(seconds, std::chrono::duration<double>(t1 - t0).count());
    }
  }
  out.ms_per_cut = 1e3 * seconds;
  return out;
}

const std::vector<std::string> kColumns = {"volume_lost_m3", "volume_lost_rel", "mean_dist_mm",
                                           "max_dist_mm",    "tets_created",    "min_quality",
                                           "ms_per_cut"};

}  // namespace

PartResult run_cutting_part(const BenchOptions& options) {
  const int n = options.quick ? 10 : 20;
  const int reps = options.quick ? 3 : 10;
  const TetMesh pristine = kuhn_grid(n, kH);
  const cutting::TetBvh pristine_bvh(pristine);
  const std::vector<NamedBlade> cuts = blades(n);

  PartResult result;
  Table summary{"cutting_methods", kColumns, {}, {}};
  Table detail{"cutting_blades", kColumns, {}, {}};
  for (const CutMethod method : {CutMethod::kPattern, CutMethod::kRemove, CutMethod::kSnap}) {
    const std::string name(cutting::to_string(method));
    double lost = 0.0, lost_rel = 0.0, mean_dist = 0.0, max_dist = 0.0, created = 0.0, ms = 0.0;
    double min_q = 1.0;
    for (const NamedBlade& b : cuts) {
      const Measured m = measure(pristine, pristine_bvh, b.polygon, method, reps);
      const cutting::CutAccuracy& a = m.accuracy;
      std::string label = name;
      label.append(" / ").append(b.name);
      detail.add(label, {a.volume_lost_m3, a.volume_lost_rel, 1e3 * a.mean_dist_m,
                         1e3 * a.max_dist_m, m.tets_created, a.min_quality, m.ms_per_cut});
      if (method == CutMethod::kPattern) {
        // The pattern method's claims: exact volume, cut surface on the blade's plane.
        if (std::abs(a.volume_lost_rel) > 1e-12) {
          std::string msg = "cutting: the pattern cut '";
          msg.append(b.name).append("' changed the volume by ");
          msg.append(std::to_string(a.volume_lost_rel)).append(" (relative; must be <= 1e-12)");
          throw std::runtime_error(msg);
        }
        if (a.cut_faces == 0 || a.max_plane_dist_m > 1e-9 * kH) {
          std::string msg = "cutting: the pattern cut '";
          msg.append(b.name).append("' left its cut surface off the blade's plane (");
          msg.append(std::to_string(a.cut_faces)).append(" faces, max distance ");
          msg.append(std::to_string(a.max_plane_dist_m)).append(" m)");
          throw std::runtime_error(msg);
        }
      }
      const double k = 1.0 / static_cast<double>(cuts.size());
      lost += k * a.volume_lost_m3;
      lost_rel += k * a.volume_lost_rel;
      mean_dist += k * 1e3 * a.mean_dist_m;
      max_dist = std::max(max_dist, 1e3 * a.max_dist_m);
      created += k * m.tets_created;
      min_q = std::min(min_q, a.min_quality);
      ms += k * m.ms_per_cut;
    }
    summary.add(name, {lost, lost_rel, mean_dist, max_dist, created, min_q, ms});
  }
  result.tables.push_back(std::move(summary));
  result.tables.push_back(std::move(detail));

  const auto method_plot = [](std::string name, std::string title, std::string y,
                              std::string y_label) {
    Plot p;
    p.name = std::move(name);
    p.title = std::move(title);
    p.x_label = "time per cut (query + cut + apply + BVH update), ms";
    p.y_label = std::move(y_label);
    p.series.push_back({"cutting_blades", "ms_per_cut", y, "each blade", true, false});
    p.series.push_back({"cutting_methods", "ms_per_cut", y, "mean over blades", true, true});
    return p;
  };
  result.plots.push_back(method_plot("cutting_volume", "Cutting: volume lost against time",
                                     "volume_lost_rel", "volume lost / volume"));
  result.plots.push_back(method_plot("cutting_distance",
                                     "Cutting: cut surface distance from the blade", "max_dist_mm",
                                     "max distance of the cut surface, mm"));
  result.plots.push_back(method_plot("cutting_quality", "Cutting: worst tet after the cut",
                                     "min_quality", "minimum mean-ratio quality"));
  std::string note = "cutting: ";
  note.append(std::to_string(pristine.num_tets()))
      .append(" tets (")
      .append(std::to_string(n))
      .append("^3 cells of 2 mm), ")
      .append(std::to_string(cuts.size()))
      .append(
          " blades, each cut on the pristine block; pattern keeps the volume and its cut "
          "surface on the blade plane (checked)");
  result.notes.push_back(std::move(note));
  return result;
}

}  // namespace serosa::bench

#include "engine/mesh_check.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "engine/mesh_quality.h"
#include "engine/tet_faces.h"

namespace serosa {

namespace {

// "N what (first: tet T)" or "N what (first in tet T)" for a problem or warning line; `first` < 0
// leaves the example out.
std::string count_line(std::int64_t n, const char* what, const char* item, std::int64_t first,
                       const std::string& detail = {}) {
  std::string s = std::to_string(n) + " " + what;
  if (first >= 0) {
    s += " (first " + std::string(item) + " " + std::to_string(first) + detail + ")";
  }
  return s;
}

// ", element E at line L of FILE" for tet t when the options know where it came from.
std::string tet_where(const MeshCheckOptions& o, std::int64_t t) {
  const auto k = static_cast<std::size_t>(t);
  if (t < 0 || k >= o.tet_lines.size()) return {};
  std::string s = ", ";
  if (k < o.tet_ids.size()) s += "element " + std::to_string(o.tet_ids[k]) + " at ";
  return s + "line " + std::to_string(o.tet_lines[k]) + " of " + o.tet_file;
}

std::string format_g(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// Array sizes that must match the node and tet counts; returns false when any does not.
bool check_sizes(const TetMesh& mesh, MeshCheckReport& r) {
  const std::size_t n = mesh.rest.size();
  const std::size_t m = mesh.tets.size();
  bool ok = true;
  const auto expect = [&](std::size_t got, std::size_t want, const char* name) {
    if (got != want) {
      r.problems.push_back(std::string("array size mismatch: ") + name + " has " +
                           std::to_string(got) + " entries, expected " + std::to_string(want));
      ok = false;
    }
  };
  expect(mesh.x.size(), n, "x");
  expect(mesh.v.size(), n, "v");
  expect(mesh.mass.size(), n, "mass");
  expect(mesh.fixed.size(), n, "fixed");
  expect(mesh.group.size(), m, "group");
  return ok;
}

// Finite coordinates and the bounding box; returns (n) 1 where a node's coordinates are finite.
std::vector<std::uint8_t> check_nodes(const TetMesh& mesh, MeshCheckReport& r) {
  const auto n = mesh.rest.size();
  std::vector<std::uint8_t> finite(n, 1);
  std::int64_t first_nonfinite = -1;
  bool any_finite = false;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3& p = mesh.rest[i];
    if (!p.allFinite()) {
      finite[i] = 0;
      if (r.nonfinite_nodes++ == 0) first_nonfinite = static_cast<std::int64_t>(i);
      continue;
    }
    r.bbox_min = any_finite ? r.bbox_min.cwiseMin(p) : p;
    r.bbox_max = any_finite ? r.bbox_max.cwiseMax(p) : p;
    any_finite = true;
  }
  if (r.nonfinite_nodes > 0) {
    r.problems.push_back(count_line(r.nonfinite_nodes, "nodes with NaN or infinite coordinates",
                                    "node:", first_nonfinite));
  }

  return finite;
}

// Node ids, volumes and quality of every tet; inverted, flat and unreferenced counts. finite: (n)
// from check_nodes; qualities: out, one per tet with valid ids and finite corners.
void check_tets(const TetMesh& mesh, const MeshCheckOptions& options,
                const std::vector<std::uint8_t>& finite, MeshCheckReport& r,
                std::vector<double>& qualities) {
  const auto n = mesh.rest.size();
  qualities.reserve(mesh.tets.size());
  std::vector<std::uint8_t> referenced(n, 0);
  std::int64_t first_bad = -1, first_inverted = -1, first_flat = -1;
  double first_inverted_volume = 0.0;
  for (std::size_t i = 0; i < mesh.tets.size(); ++i) {
    const Tet& t = mesh.tets[i];
    const int g = i < mesh.group.size() ? mesh.group[i] : 0;
    ++r.group_tets[g];
    bool ids_ok = true;
    for (const std::int32_t id : t) ids_ok = ids_ok && id >= 0 && static_cast<std::size_t>(id) < n;
    if (!ids_ok) {
      if (r.bad_tets++ == 0) first_bad = static_cast<std::int64_t>(i);
      continue;
    }
    bool geometry_ok = true;
    for (const std::int32_t id : t) {
      referenced[static_cast<std::size_t>(id)] = 1;
      geometry_ok = geometry_ok && finite[static_cast<std::size_t>(id)];
    }
    if (!geometry_ok) continue;
    const Vec3& a = mesh.rest[static_cast<std::size_t>(t[0])];
    const Vec3& b = mesh.rest[static_cast<std::size_t>(t[1])];
    const Vec3& c = mesh.rest[static_cast<std::size_t>(t[2])];
    const Vec3& d = mesh.rest[static_cast<std::size_t>(t[3])];
    const double vol = signed_volume(a, b, c, d);
    r.volume_m3 += vol;
    r.group_volume_m3[g] += vol;
    qualities.push_back(tet_quality(a, b, c, d));
    const double mean_edge = ((b - a).norm() + (c - a).norm() + (d - a).norm() + (c - b).norm() +
                              (d - b).norm() + (d - c).norm()) /
                             6.0;
    if (std::abs(vol) <= options.flat_tolerance * mean_edge * mean_edge * mean_edge) {
      if (r.flat_tets++ == 0) first_flat = static_cast<std::int64_t>(i);
    } else if (vol < 0.0) {
      if (r.inverted_tets++ == 0) {
        first_inverted = static_cast<std::int64_t>(i);
        first_inverted_volume = vol;
      }
    }
  }
  if (r.bad_tets > 0) {
    const Tet& t = mesh.tets[static_cast<std::size_t>(first_bad)];
    r.problems.push_back(
        count_line(r.bad_tets, "tets with a node id out of range", "tet:", first_bad,
                   tet_where(options, first_bad) + ", ids " + std::to_string(t[0]) + " " +
                       std::to_string(t[1]) + " " + std::to_string(t[2]) + " " +
                       std::to_string(t[3]) + " with " + std::to_string(n) + " nodes"));
  }
  if (r.inverted_tets > 0) {
    r.problems.push_back(count_line(r.inverted_tets, "inverted tets", "tet:", first_inverted,
                                    tet_where(options, first_inverted) + ", volume " +
                                        format_g(first_inverted_volume) + " m^3"));
  }
  if (r.flat_tets > 0) {
    r.problems.push_back(count_line(r.flat_tets, "flat (zero-volume) tets", "tet:", first_flat,
                                    tet_where(options, first_flat)));
  }
  for (std::size_t i = 0; i < n; ++i) r.unreferenced_nodes += referenced[i] ? 0 : 1;
  if (r.unreferenced_nodes > 0) {
    const auto it = std::find(referenced.begin(), referenced.end(), std::uint8_t{0});
    r.warnings.push_back(
        count_line(r.unreferenced_nodes, "nodes used by no tet", "node:", it - referenced.begin()));
  }
}

void summarize_quality(std::vector<double>& qualities, MeshCheckReport& r) {
  if (qualities.empty()) return;
  std::sort(qualities.begin(), qualities.end());
  r.min_quality = qualities.front();
  const std::size_t k = qualities.size();
  r.median_quality =
      k % 2 == 1 ? qualities[k / 2] : 0.5 * (qualities[k / 2 - 1] + qualities[k / 2]);
}

// Boundary, interior, overshared and misoriented faces.
void check_faces(const TetMesh& mesh, const MeshCheckOptions& options, MeshCheckReport& r) {
  const std::vector<TetFace> faces = sorted_tet_faces(mesh.tets);
  std::int64_t first_overshared = -1, first_misoriented = -1;
  for (std::size_t i = 0; i < faces.size();) {
    std::size_t j = i + 1;
    while (j < faces.size() && faces[j].key == faces[i].key) ++j;
    const std::size_t count = j - i;
    if (count == 1) {
      ++r.boundary_faces;
    } else if (count == 2) {
      ++r.interior_faces;
      // Two tets on opposite sides of a face wind it oppositely.
      if (faces[i].parity == faces[i + 1].parity) {
        if (r.misoriented_faces++ == 0) first_misoriented = faces[i].tet;
      }
    } else {
      if (r.overshared_faces++ == 0) first_overshared = faces[i].tet;
    }
    i = j;
  }
  if (r.overshared_faces > 0) {
    r.problems.push_back(count_line(r.overshared_faces, "faces shared by more than two tets",
                                    "in tet", first_overshared,
                                    tet_where(options, first_overshared)));
  }
  if (r.misoriented_faces > 0) {
    r.problems.push_back(count_line(
        r.misoriented_faces, "faces shared by two tets on the same side (overlapping tets)",
        "in tet", first_misoriented, tet_where(options, first_misoriented)));
  }
}

// Tets with the same four nodes as another.
void check_duplicates(const TetMesh& mesh, const MeshCheckOptions& options, MeshCheckReport& r) {
  std::vector<std::pair<Tet, std::int32_t>> sorted_tets;
  sorted_tets.reserve(mesh.tets.size());
  for (std::size_t i = 0; i < mesh.tets.size(); ++i) {
    Tet t = mesh.tets[i];
    std::sort(t.begin(), t.end());
    sorted_tets.emplace_back(t, static_cast<std::int32_t>(i));
  }
  std::sort(sorted_tets.begin(), sorted_tets.end());
  std::int64_t first_duplicate = -1;
  for (std::size_t i = 1; i < sorted_tets.size(); ++i) {
    if (sorted_tets[i].first == sorted_tets[i - 1].first) {
      ++r.duplicate_tets;
      if (first_duplicate < 0 || sorted_tets[i].second < first_duplicate) {
        first_duplicate = sorted_tets[i].second;
      }
    }
  }
  if (r.duplicate_tets > 0) {
    r.problems.push_back(count_line(r.duplicate_tets, "duplicated tets (same nodes as another)",
                                    "tet:", first_duplicate, tet_where(options, first_duplicate)));
  }
}

}  // namespace

MeshCheckReport check_mesh(const TetMesh& mesh, const MeshCheckOptions& options) {
  MeshCheckReport r;
  r.nodes = static_cast<std::int64_t>(mesh.rest.size());
  r.tets = static_cast<std::int64_t>(mesh.tets.size());
  const bool sizes_ok = check_sizes(mesh, r);
  if (r.tets == 0) r.problems.push_back("no tetrahedra");
  const std::vector<std::uint8_t> finite = check_nodes(mesh, r);
  std::vector<double> qualities;
  check_tets(mesh, options, finite, r, qualities);
  summarize_quality(qualities, r);
  check_faces(mesh, options, r);
  check_duplicates(mesh, options, r);
  r.valid = sizes_ok && r.problems.empty();
  return r;
}

}  // namespace serosa

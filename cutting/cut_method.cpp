#include "cutting/cut_method.h"

#include "cutting/remove_cut.h"
#include "cutting/snap_cut.h"

namespace serosa::cutting {

std::string_view to_string(CutMethod method) {
  switch (method) {
    case CutMethod::kPattern:
      return "pattern";
    case CutMethod::kRemove:
      return "remove";
    case CutMethod::kSnap:
      return "snap";
  }
  return "pattern";
}

std::optional<CutMethod> parse_cut_method(std::string_view name) {
  for (CutMethod m : {CutMethod::kPattern, CutMethod::kRemove, CutMethod::kSnap})
    if (name == to_string(m)) return m;
  return std::nullopt;
}

CutResult cut_with(CutMethod method, const TetMesh& mesh, const ConvexPolygon& blade,
                   const CutOptions& options, const TetBoxQuery& query) {
  switch (method) {
    case CutMethod::kRemove:
      return remove_cut(mesh, blade, options, query);
    case CutMethod::kSnap: {
      SnapOptions so;
      so.classify_rel = options.classify_rel;
      return snap_cut(mesh, blade, so, query);
    }
    case CutMethod::kPattern:
      break;
  }
  return cut_mesh(mesh, blade, options, query);
}

}  // namespace serosa::cutting

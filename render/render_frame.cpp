// RenderFrame validation (see render_frame.h).
#include "render/render_frame.h"

#include <algorithm>

namespace serosa::render {
namespace {

// Appends a message when an id in `ids` is not below `n`.
void check_ids(const std::vector<std::uint32_t>& ids, std::size_t n, const char* what,
               std::vector<std::string>& errors) {
  const auto bad = std::find_if(ids.begin(), ids.end(), [n](std::uint32_t id) { return id >= n; });
  if (bad != ids.end()) {
    errors.push_back(std::string(what) + " uses vertex " + std::to_string(*bad) + " of " +
                     std::to_string(n));
  }
}

}  // namespace

std::vector<std::string> validate(const RenderFrame& frame) {
  std::vector<std::string> errors;
  const std::size_t n = frame.num_vertices();
  const std::size_t t = frame.num_triangles();
  if (frame.pos.size() % 3 != 0) errors.emplace_back("pos is not n x 3");
  if (!frame.nrm.empty() && frame.nrm.size() != frame.pos.size()) {
    errors.emplace_back("nrm is neither empty nor n x 3");
  }
  if (frame.tri.size() % 3 != 0) errors.emplace_back("tri is not t x 3");
  if (!frame.tri_group.empty() && frame.tri_group.size() != t) {
    errors.emplace_back("tri_group is neither empty nor one per triangle");
  }
  if (!frame.tri_cut.empty() && frame.tri_cut.size() != t) {
    errors.emplace_back("tri_cut is neither empty nor one per triangle");
  }
  if (frame.edges.size() % 2 != 0) errors.emplace_back("edges is not e x 2");
  check_ids(frame.tri, n, "tri", errors);
  check_ids(frame.edges, n, "edges", errors);
  return errors;
}

}  // namespace serosa::render

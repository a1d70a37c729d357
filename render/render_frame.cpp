// RenderFrame validation (see render_frame.h).
#include "render/render_frame.h"

#include <algorithm>
#include <cmath>
#include <numbers>

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

// Appends the scenery's shape and id problems (see validate).
void check_scenery(const Scenery& s, std::vector<std::string>& errors) {
  if (s.pos.size() % 3 != 0) errors.emplace_back("scenery pos is not n x 3");
  if (s.nrm.size() != s.pos.size()) errors.emplace_back("scenery nrm is not n x 3");
  if (s.tri.size() % 3 != 0) errors.emplace_back("scenery tri is not t x 3");
  if (s.material.size() != s.num_triangles())
    errors.emplace_back("scenery material is not one per triangle");
  check_ids(s.tri, s.num_vertices(), "scenery tri", errors);
  const auto finite = [](const std::vector<float>& a) {
    return std::all_of(a.begin(), a.end(), [](float v) { return std::isfinite(v); });
  };
  if (!finite(s.pos) || !finite(s.nrm)) errors.emplace_back("scenery has a non-finite value");
  const auto bad = std::find_if(s.material.begin(), s.material.end(),
                                [](SceneryMaterial m) { return m > SceneryMaterial::kFat; });
  if (bad != s.material.end()) errors.emplace_back("scenery has an unknown material");
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
  if (!frame.rest.empty() && frame.rest.size() != frame.pos.size()) {
    errors.emplace_back("rest is neither empty nor n x 3");
  }
  if (!frame.rim.empty() && frame.rim.size() != n) {
    errors.emplace_back("rim is neither empty nor one per vertex");
  }
  if (!frame.stain.empty() && frame.stain.size() != n) {
    errors.emplace_back("stain is neither empty nor one per vertex");
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
  for (std::size_t i = 0; i < frame.tools.size(); ++i) {
    const RenderTool& tool = frame.tools[i];
    bool finite = std::isfinite(tool.jaw_rad);
    for (const float c : tool.tip) finite = finite && std::isfinite(c);
    for (const float c : tool.trocar) finite = finite && std::isfinite(c);
    float qn = 0.0f;
    for (const float c : tool.quat_wxyz) {
      finite = finite && std::isfinite(c);
      qn += c * c;
    }
    std::string what = "tools[";
    what.append(std::to_string(i)).append("]");
    if (!finite) {
      errors.push_back(what + " has a non-finite value");
    } else {
      if (tool.jaw_rad < 0.0f || tool.jaw_rad > std::numbers::pi_v<float>)
        errors.push_back(what + " jaw_rad is outside [0, pi]");
      if (qn < 1e-12f) errors.push_back(what + " quaternion is zero");
    }
  }
  for (std::size_t i = 0; i < frame.clips.size(); ++i) {
    const RenderClip& c = frame.clips[i];
    bool finite = true;
    for (const auto* a : {&c.start, &c.end, &c.across})
      for (const float v : *a) finite = finite && std::isfinite(v);
    if (!finite) errors.push_back("clips[" + std::to_string(i) + "] has a non-finite value");
  }
  check_scenery(frame.scenery, errors);
  return errors;
}

}  // namespace serosa::render

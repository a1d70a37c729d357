#include "window/view_log.h"

#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "engine/input_error.h"
#include "render/camera.h"
#include "render/tool_mesh.h"

namespace serosa::window {
namespace {

using Json = nlohmann::json;
using V3 = Eigen::Vector3f;

// Projects world points into the window's pixels with the frame's camera.
class Projector {
 public:
  Projector(const render::RenderFrame& frame, int width, int height)
      : m_width(static_cast<float>(width)), m_height(static_cast<float>(height)) {
    const float aspect = m_width / std::max(m_height, 1.0f);
    render::Bounds b = render::drawn_bounds(frame);
    if (b.empty) {
      b.lo = V3::Constant(-1.0f);
      b.hi = V3::Constant(1.0f);
      b.empty = false;
    }
    const render::CameraMatrices m = render::camera_matrices(frame.camera, aspect, b);
    m_view_proj = m.projection * m.view;
    m_view = m.view;
  }
  // {"px": [x, y], "depth_m": d}: d along the view, m (negative: behind the camera).
  [[nodiscard]] Json at(const V3& p) const {
    const Eigen::Vector4f c = m_view_proj * Eigen::Vector4f(p.x(), p.y(), p.z(), 1.0f);
    const Eigen::Vector4f e = m_view * Eigen::Vector4f(p.x(), p.y(), p.z(), 1.0f);
    const float w = std::abs(c.w()) > 1e-12f ? c.w() : 1e-12f;
    return {{"px", {(0.5f * c.x() / w + 0.5f) * m_width, (0.5f - 0.5f * c.y() / w) * m_height}},
            {"depth_m", -e.z()}};
  }

 private:
  float m_width, m_height;
  Eigen::Matrix4f m_view_proj;
  Eigen::Matrix4f m_view;
};

V3 vec(const std::array<float, 3>& a) { return {a[0], a[1], a[2]}; }

Json tool_json(const render::RenderTool& t, const Projector& p) {
  const render::ToolDimensions dims;
  const render::ToolFrame f = render::tool_frame(t, dims);
  const float length =
      t.kind == render::RenderTool::Kind::kScissors ? dims.scissors_blade : dims.grasper_jaw;
  const V3 hinge = vec(f.hinge), axis = vec(f.axis), side = vec(f.side);
  const float a = 0.5f * t.jaw_rad;
  Json j{{"scene_tool", t.scene_tool},
         {"active", t.active},
         {"jaw_rad", t.jaw_rad},
         {"tip", p.at(vec(t.tip))},
         {"jaw_mid", p.at(hinge + 0.5f * length * axis)},
         {"jaw_tips",
          {p.at(hinge + length * (std::cos(a) * axis + std::sin(a) * side)),
           p.at(hinge + length * (std::cos(a) * axis - std::sin(a) * side))}},
         {"shaft", p.at(hinge - 0.03f * axis)}};
  if (t.has_tissue) j["tissue_distance_m"] = t.tissue_distance_m;
  j["tissue_in_jaws_m"] = t.tissue_in_jaws_m;
  return j;
}

// The centroid of each group's drawn surface vertices.
Json groups_json(const render::RenderFrame& frame, const Projector& p) {
  std::map<std::uint16_t, std::pair<V3, int>> sums;
  for (std::size_t t = 0; t < frame.tri_group.size(); ++t) {
    auto& [sum, n] = sums.try_emplace(frame.tri_group[t], V3::Zero(), 0).first->second;
    for (int k = 0; k < 3; ++k) {
      const std::size_t v = frame.tri[3 * t + static_cast<std::size_t>(k)];
      sum += V3(frame.pos[3 * v], frame.pos[3 * v + 1], frame.pos[3 * v + 2]);
      ++n;
    }
  }
  Json j = Json::object();
  for (const auto& [g, s] : sums) {
    const std::string name = g < frame.group_names.size() && !frame.group_names[g].empty()
                                 ? frame.group_names[g]
                                 : std::to_string(g);
    j[name] = p.at(s.first / static_cast<float>(std::max(s.second, 1)));
  }
  return j;
}

}  // namespace

ViewLog::ViewLog(const std::filesystem::path& file, std::vector<std::string> tools)
    : m_file(file), m_tools(std::move(tools)), m_out(file) {
  if (!m_out) throw InputError(file.string(), 0, "cannot write the view log", "a writable path");
}

void ViewLog::write(const render::RenderFrame& frame, int width, int height, double wall_s,
                    int active_hand) {
  const Projector p(frame, width, height);
  Json line{{"wall_s", wall_s},
            {"sim_time_s", frame.overlay.sim_time_s},
            {"width", width},
            {"height", height},
            {"active_hand", active_hand}};
  line["tools"] = Json::array();
  for (const render::RenderTool& t : frame.tools) {
    line["tools"].push_back(tool_json(t, p));
    if (t.scene_tool < m_tools.size()) line["tools"].back()["tool"] = m_tools[t.scene_tool];
  }
  line["guide"] = Json::array();
  for (const auto& g : frame.guide) line["guide"].push_back(p.at(vec(g)));
  line["groups"] = groups_json(frame, p);
  line["hands"] = Json::array();
  for (const render::OverlayHand& h : frame.overlay.hands)
    line["hands"].push_back({{"hand", h.hand},
                             {"tool", h.tool},
                             {"active", h.active},
                             {"jaw_rad", h.jaw_rad},
                             {"jaw_max_rad", h.jaw_max_rad},
                             {"pedal", h.pedal},
                             {"holding_nodes", h.holding_nodes}});
  m_out << line.dump() << '\n' << std::flush;
  if (!m_out) throw InputError(m_file.string(), 0, "cannot write the view log", "a writable path");
}

}  // namespace serosa::window

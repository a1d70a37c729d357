#include "render/overlay_timeline.h"

#include <imgui.h>

#include <algorithm>
#include <vector>

namespace serosa::render {
namespace {

constexpr float kPlotHeight = 36.0f;  // px
constexpr ImU32 kMarkColour = IM_COL32(235, 64, 52, 255);
constexpr ImU32 kCurrentColour = IM_COL32(255, 214, 10, 255);
constexpr ImU32 kPositionColour = IM_COL32(255, 255, 255, 220);

}  // namespace

void draw_timeline(const OverlayData& data, const std::string& errors_line) {
  const OverlayTimeline& tl = data.timeline;
  // Bins not computed yet plot as 0, and the plot's scale is the largest force known so far.
  std::vector<float> force(tl.force_n.size());
  float top = 1.0f;
  for (std::size_t i = 0; i < force.size(); ++i) {
    force[i] = std::max(tl.force_n[i], 0.0f);
    top = std::max(top, force[i]);
  }
  char label[48];
  std::snprintf(label, sizeof label, "force on the tissue, N (max %.1f)", static_cast<double>(top));
  ImGui::PlotLines("##force", force.empty() ? nullptr : force.data(),
                   static_cast<int>(force.size()), 0, label, 0.0f, 1.05f * top,
                   ImVec2(ImGui::GetContentRegionAvail().x, kPlotHeight));
  const ImVec2 lo = ImGui::GetItemRectMin();
  const ImVec2 hi = ImGui::GetItemRectMax();
  const double duration = std::max(data.replay_duration_s, 1e-6);
  const auto x_at = [&](double t) {
    return lo.x + static_cast<float>(std::clamp(t / duration, 0.0, 1.0)) * (hi.x - lo.x);
  };
  ImDrawList* draw = ImGui::GetWindowDrawList();
  for (std::size_t k = 0; k < tl.marks.size(); ++k) {
    const float x = x_at(tl.marks[k].time_s);
    const bool current = static_cast<int>(k) == tl.current;
    draw->AddLine(ImVec2(x, lo.y), ImVec2(x, hi.y), current ? kCurrentColour : kMarkColour,
                  current ? 3.0f : 2.0f);
  }
  const float now = x_at(data.replay_position_s);
  draw->AddLine(ImVec2(now, lo.y), ImVec2(now, hi.y), kPositionColour, 1.0f);
  ImGui::TextUnformatted(errors_line.c_str());
}

}  // namespace serosa::render

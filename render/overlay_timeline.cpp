#include "render/overlay_timeline.h"

#include <imgui.h>

#include <algorithm>
#include <string>
#include <vector>

namespace serosa::render {
namespace {

constexpr float kPlotHeight = 36.0f;  // px
constexpr ImU32 kMarkColour = IM_COL32(235, 64, 52, 255);
constexpr ImU32 kCurrentColour = IM_COL32(255, 214, 10, 255);
constexpr ImU32 kPositionColour = IM_COL32(255, 255, 255, 220);
constexpr ImU32 kStepColours[2] = {IM_COL32(52, 101, 164, 230), IM_COL32(78, 154, 6, 230)};
constexpr ImU32 kBranchColour = IM_COL32(196, 120, 0, 235);
constexpr float kStepRowHeight = 18.0f;  // px

// The procedure's steps under the plot, between lo.x and hi.x (the plot's width).
void draw_steps(const std::vector<SummaryStep>& steps, double duration, float lo_x, float hi_x) {
  const ImVec2 at = ImGui::GetCursorScreenPos();
  ImGui::Dummy(ImVec2(hi_x - lo_x, kStepRowHeight));
  ImDrawList* draw = ImGui::GetWindowDrawList();
  const auto x_at = [&](double t) {
    return lo_x + static_cast<float>(std::clamp(t / duration, 0.0, 1.0)) * (hi_x - lo_x);
  };
  std::string not_done;
  int k = 0;
  for (const SummaryStep& st : steps) {
    if (!st.done) {
      not_done.append(not_done.empty() ? "not done: " : ", ").append(st.name);
      continue;
    }
    const ImVec2 a(x_at(st.start_s) + 1.0f, at.y);
    const ImVec2 b(std::max(x_at(st.start_s + st.duration_s) - 1.0f, a.x + 2.0f),
                   at.y + kStepRowHeight);
    draw->AddRectFilled(a, b, kStepColours[k++ % 2], 3.0f);
    const std::string label = st.name + " (" + st.tool + ")";
    draw->PushClipRect(a, b, true);
    draw->AddText(ImVec2(a.x + 4.0f, a.y + 2.0f), IM_COL32(255, 255, 255, 255), label.c_str());
    draw->PopClipRect();
  }
  if (!not_done.empty())
    ImGui::TextColored(ImVec4(1.0f, 0.55f, 0.45f, 1.0f), "%s", not_done.c_str());
}

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
  if (data.debrief && !data.debrief->steps.empty())
    draw_steps(data.debrief->steps, duration, lo.x, hi.x);
  ImGui::TextUnformatted(errors_line.c_str());
}

void draw_branch_band(const std::string& text) {
  const ImVec2 at = ImGui::GetCursorScreenPos();
  const float w = ImGui::GetContentRegionAvail().x;
  // As many lines as the text takes at the band's width.
  const float h = ImGui::CalcTextSize(text.c_str(), nullptr, false, w - 12.0f).y + 6.0f;
  ImGui::GetWindowDrawList()->AddRectFilled(at, ImVec2(at.x + w, at.y + h), kBranchColour, 3.0f);
  ImGui::SetCursorScreenPos(ImVec2(at.x + 6.0f, at.y + 3.0f));
  ImGui::PushTextWrapPos(ImGui::GetCursorPos().x + w - 12.0f);
  ImGui::TextUnformatted(text.c_str());
  ImGui::PopTextWrapPos();
  ImGui::SetCursorScreenPos(ImVec2(at.x, at.y + h + 2.0f));
  ImGui::Dummy(ImVec2(0.0f, 0.0f));
}

}  // namespace serosa::render

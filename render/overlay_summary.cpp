// Overlay::draw_summary (see overlay.h): the end-of-session summary, a centred panel with a
// coloured banner (green: passed, red: not) over the last picture.
#include <imgui.h>

#include <algorithm>
#include <cfloat>

#include "render/overlay.h"
#include "render/overlay_debrief.h"

namespace serosa::render {

namespace {

ImVec4 colour(const unsigned char rgb[3]) {
  return ImVec4(rgb[0] / 255.0f, rgb[1] / 255.0f, rgb[2] / 255.0f, 1.0f);
}

void layout_summary(const SessionSummary& s, int width, int height) {
  const float w = std::min(560.0f, 0.9f * static_cast<float>(width));
  ImGui::SetNextWindowPos(
      ImVec2(0.5f * static_cast<float>(width), 0.5f * static_cast<float>(height)), ImGuiCond_Always,
      ImVec2(0.5f, 0.5f));
  ImGui::SetNextWindowSize(ImVec2(w, 0.0f), ImGuiCond_Always);
  ImGui::SetNextWindowSizeConstraints(ImVec2(w, 0.0f),
                                      ImVec2(w, 0.95f * static_cast<float>(height)));
  ImGui::SetNextWindowBgAlpha(0.9f);
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove |
                                 ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoNav;
  if (ImGui::Begin("Summary", nullptr, flags)) debrief_contents(s, true);
  ImGui::End();
}

}  // namespace

void debrief_contents(const SessionSummary& s, bool with_way_out) {
  const std::vector<std::string> lines = summary_text(s, with_way_out);
  ImGui::PushTextWrapPos(0.0f);              // wrap at the panel's edge
  ImGui::TextUnformatted(lines[0].c_str());  // the title
  // The banner: a solid bar the width of the panel, the verdict on it.
  const ImVec2 at = ImGui::GetCursorScreenPos();
  const float bar_h = 2.0f * ImGui::GetTextLineHeight();
  const ImVec4 c = colour(s.passed ? kPassedRgb : kFailedRgb);
  ImGui::GetWindowDrawList()->AddRectFilled(
      at, ImVec2(at.x + std::max(ImGui::GetContentRegionAvail().x, 200.0f), at.y + bar_h),
      ImGui::ColorConvertFloat4ToU32(c));
  ImGui::SetCursorScreenPos(ImVec2(at.x + 10.0f, at.y + 0.25f * bar_h));
  ImGui::TextUnformatted(lines[1].c_str());
  ImGui::SetCursorScreenPos(ImVec2(at.x, at.y + bar_h + 6.0f));
  const std::size_t body_end = with_way_out ? lines.size() - 1 : lines.size();
  for (std::size_t i = 2; i < body_end; ++i) ImGui::TextUnformatted(lines[i].c_str());
  for (const SummaryGroup& g : s.groups) {
    if (!ImGui::CollapsingHeader(g.domain.c_str())) continue;  // collapsed until opened
    for (const std::string& l : g.lines) ImGui::TextUnformatted(l.c_str());
  }
  ImGui::PopTextWrapPos();
  if (with_way_out) {
    ImGui::Separator();
    ImGui::TextDisabled("%s", lines.back().c_str());
  }
}

void Overlay::draw_summary(const SessionSummary& summary, int width, int height) {
  if (width <= 0 || height <= 0) return;
  ImGui::SetCurrentContext(imgui_);
  ImGuiIO& io = ImGui::GetIO();
  io.DisplaySize = ImVec2(static_cast<float>(width), static_cast<float>(height));
  io.DisplayFramebufferScale = ImVec2(1.0f, 1.0f);
  io.DeltaTime = 1.0f / 60.0f;
  io.MousePos = ImVec2(-FLT_MAX, -FLT_MAX);
  io.MouseDown[0] = false;
  // An auto-sized panel measures itself on its first frame: lay out one throw-away frame.
  ImGui::NewFrame();
  layout_summary(summary, width, height);
  ImGui::EndFrame();
  ImGui::NewFrame();
  layout_summary(summary, width, height);
  ImGui::Render();
  render_draw_data();
}

}  // namespace serosa::render

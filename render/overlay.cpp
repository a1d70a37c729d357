// Overlay (see overlay.h): ImGui layout and a minimal OpenGL 3 renderer for ImDrawData.
#include "render/overlay.h"
#include "render/overlay_debrief.h"
#include "render/overlay_timeline.h"

#include <epoxy/gl.h>
#include <imgui.h>

#include <algorithm>
#include <array>
#include <cfloat>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "render/gl_program.h"

namespace serosa::render {
namespace {

const char* const kOverlayVertex = R"(#version 410 core
layout(location = 0) in vec2 a_pos;    // pixels, origin top left
layout(location = 1) in vec2 a_uv;
layout(location = 2) in vec4 a_color;  // sRGB, normalised bytes
uniform vec2 u_size;                   // framebuffer size, pixels
out vec2 v_uv;
out vec4 v_color;
void main() {
  v_uv = a_uv;
  v_color = a_color;
  gl_Position = vec4(2.0 * a_pos.x / u_size.x - 1.0, 1.0 - 2.0 * a_pos.y / u_size.y, 0.0, 1.0);
}
)";

const char* const kOverlayFragment = R"(#version 410 core
in vec2 v_uv;
in vec4 v_color;
uniform sampler2D u_font;
out vec4 frag_color;
void main() { frag_color = v_color * texture(u_font, v_uv); }
)";

constexpr std::array<SnapshotOptions::View, 3> kViews{SnapshotOptions::View::kVisual,
                                                      SnapshotOptions::View::kCollision,
                                                      SnapshotOptions::View::kMechanical};

std::array<float, 4> last_item_rect() {
  const ImVec2 lo = ImGui::GetItemRectMin();
  const ImVec2 hi = ImGui::GetItemRectMax();
  return {lo.x, lo.y, hi.x, hi.y};
}

ImTextureID texture_id(GLuint tex) {
  return reinterpret_cast<ImTextureID>(static_cast<std::uintptr_t>(tex));
}

GLuint gl_texture(ImTextureID id) {
  return static_cast<GLuint>(reinterpret_cast<std::uintptr_t>(id));
}

// "m:ss.s" for the timeline.
void format_time(double s, char* out, std::size_t size) {
  s = std::max(s, 0.0);
  const int minutes = static_cast<int>(s / 60.0);
  std::snprintf(out, size, "%d:%04.1f", minutes, s - 60.0 * minutes);
}

std::string hand_line(const OverlayHand& h) {
  std::string l = h.active ? "> " : "  ";
  l.append(h.hand).append(": ").append(h.tool);
  char part[96];
  if (h.jaw_max_rad > 0.0) {
    if (h.jaw_rad < 0.02)
      std::snprintf(part, sizeof part, "  jaws closed");
    else
      std::snprintf(part, sizeof part, "  jaws %.2f of %.2f rad", h.jaw_rad, h.jaw_max_rad);
    l.append(part);
  }
  if (h.has_pedal) l.append(h.pedal ? "  pedal DOWN" : "  pedal up");
  if (h.holding_nodes > 0) l.append("  HOLDING");
  if (h.entering) {
    l.append("  in its port: draw the handle back");
    return l;
  }
  if (h.tissue_in_jaws_m > 0.0) {
    std::snprintf(part, sizeof part, "  %.0f mm IN JAWS", 1e3 * h.tissue_in_jaws_m);
    l.append(part);
  }
  if (!h.has_tissue) {
    l.append("  tissue far");
  } else {
    if (h.tissue_distance_m <= 5e-4)
      std::snprintf(part, sizeof part, "  touching");
    else
      std::snprintf(part, sizeof part, "  tissue %.0f mm", 1e3 * h.tissue_distance_m);
    l.append(part);
  }
  return l;
}

}  // namespace

const std::vector<std::string>& overlay_help_lines() {
  static const std::vector<std::string> lines = {
      "Controls (H or F1 shows and hides this)",
      "drag (left button)  move the active instrument's tip",
      "                    the way the pointer goes",
      "W / S               move it into / out of the picture",
      "wheel               push it in / pull it back along its shaft",
      "Q / E               roll it",
      "J                   tap: open or close the jaws (the instruments",
      "                    panel says how many mm of tissue are IN JAWS)",
      "                    hold: close them slowly (bite)",
      "P                   cautery pedal down / up (hook)",
      "Home                bring it back into view",
      "Tab                 switch hands (the active one: > and a collar)",
      "X                   exchange the active hand's instrument for the",
      "                    next one waiting in its port",
      "drag (right button) turn the endoscope; I / K in / out",
      ", / .               rotate the endoscope; O 0/30 degree optic",
      "Space               pause       V  views       F2  overlay",
      "Esc                 end the session and see the score",
      "The ring on the tissue under a tip closes in as it comes near",
      "and lights up when it touches.",
  };
  return lines;
}

OverlayText overlay_text(const OverlayData& data) {
  OverlayText t;
  char line[160];
  char pace[48] = "";
  if (data.real_time_factor > 0.0)
    std::snprintf(pace, sizeof pace, "  x%.2f real time", data.real_time_factor);
  std::snprintf(line, sizeof line, "t = %.2f s%s%s%s", data.sim_time_s, pace,
                data.paused ? "  [paused]" : "", data.slow_motion ? "  [slow motion]" : "");
  t.stats.emplace_back(line);
  std::snprintf(line, sizeof line, "FEM %.2f ms/step  (%.0f steps/s)", data.fem_ms_per_step,
                data.solver_rate_hz);
  t.stats.emplace_back(line);
  char drive[64] = "";
  if (data.instruments != nullptr) std::snprintf(drive, sizeof drive, "  (%s)", data.instruments);
  if (data.haptic_rate_hz > 0.0) {
    std::snprintf(line, sizeof line, "haptics %.0f Hz%s", data.haptic_rate_hz, drive);
  } else {
    std::snprintf(line, sizeof line, "haptics \u2014%s", drive);
  }
  t.stats.emplace_back(line);
  if (data.frame_rate_hz > 0.0) {
    std::snprintf(line, sizeof line, "cuts %lld   %.0f frames/s, tess %d, %.0f%% res",
                  static_cast<long long>(data.cuts), data.frame_rate_hz, data.drawn_tessellation,
                  100.0 * static_cast<double>(data.drawn_scale));
  } else {
    std::snprintf(line, sizeof line, "cuts %lld", static_cast<long long>(data.cuts));
  }
  t.stats.emplace_back(line);
  for (const OverlayMetric& m : data.metrics) {
    std::string l = m.name;
    std::snprintf(line, sizeof line, " %.3g", m.value);
    l.append(line);
    if (!m.unit.empty()) l.append(" ").append(m.unit);
    t.stats.push_back(std::move(l));
  }
  for (const OverlayHand& h : data.hands) t.hands.push_back(hand_line(h));
  if (!data.waiting.empty()) {
    std::string l = "waiting in ports (X):";
    for (const std::string& w : data.waiting) l.append(" ").append(w);
    t.hands.push_back(std::move(l));
  }
  if (data.replay) {
    char now[32];
    char total[32];
    format_time(data.replay_position_s, now, sizeof now);
    format_time(data.replay_duration_s, total, sizeof total);
    // A branch may play on past the recording's end: its clock is its own.
    std::snprintf(
        line, sizeof line,
        data.branch.empty() ? "%s / %s  x%.2g%s" : "%s in the branch (recording %s)  x%.2g%s", now,
        total, data.replay_speed, data.paused ? "  [paused]" : "");
    t.timeline = line;
    const OverlayTimeline& tl = data.timeline;
    const auto n = static_cast<int>(tl.marks.size());
    if (!data.branch.empty())
      t.errors = "errors " + std::to_string(n) +
                 " (the recording's before the branch, the branch's own after; no seeking in a "
                 "branch)";
    else if (!tl.done)
      t.errors = "assessing the recording ... (its errors are marked when it is done)";
    else if (n == 0)
      t.errors = "no errors: every criterion passed";
    else
      t.errors = "errors " + std::to_string(n) + " (N: next, P: previous)";
    if (tl.current >= 0 && tl.current < n) {
      const TimelineMark& m = tl.marks[static_cast<std::size_t>(tl.current)];
      format_time(m.time_s, now, sizeof now);
      std::snprintf(line, sizeof line, "  %d/%d %s ", tl.current + 1, n, now);
      t.errors += line;
      t.errors += m.what;
    }
  }
  return t;
}

const char* view_name(SnapshotOptions::View view) {
  switch (view) {
    case SnapshotOptions::View::kVisual:
      return "visual";
    case SnapshotOptions::View::kCollision:
      return "collision";
    case SnapshotOptions::View::kMechanical:
      return "mechanical";
  }
  return "?";
}

Overlay::Overlay()
    : program_(std::make_unique<GlProgram>(
          std::vector<ShaderSource>{{GL_VERTEX_SHADER, kOverlayVertex, "overlay vertex"},
                                    {GL_FRAGMENT_SHADER, kOverlayFragment, "overlay fragment"}})) {
  IMGUI_CHECKVERSION();
  ImGuiContext* previous = ImGui::GetCurrentContext();
  imgui_ = ImGui::CreateContext();
  ImGui::SetCurrentContext(imgui_);
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // no imgui.ini next to the trainee's working directory
  io.LogFilename = nullptr;
  io.BackendRendererName = "serosa_gl41";
  ImGui::StyleColorsDark();
  ImGuiStyle& style = ImGui::GetStyle();
  style.WindowRounding = 4.0f;
  style.WindowBorderSize = 0.0f;

  // The font atlas as an RGBA texture.
  unsigned char* pixels = nullptr;
  int w = 0;
  int h = 0;
  io.Fonts->GetTexDataAsRGBA32(&pixels, &w, &h);
  glGenTextures(1, &font_tex_);
  glBindTexture(GL_TEXTURE_2D, font_tex_);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE, pixels);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glBindTexture(GL_TEXTURE_2D, 0);
  io.Fonts->SetTexID(texture_id(font_tex_));

  // ImDrawVert: pos (2 floats), uv (2 floats), col (4 bytes).
  glGenVertexArrays(1, &vao_);
  glGenBuffers(1, &vbo_);
  glGenBuffers(1, &ibo_);
  glBindVertexArray(vao_);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ibo_);
  const auto stride = static_cast<GLsizei>(sizeof(ImDrawVert));
  const auto offset = [](std::size_t bytes) {
    return reinterpret_cast<const void*>(static_cast<std::uintptr_t>(bytes));
  };
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, stride, offset(offsetof(ImDrawVert, pos)));
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, stride, offset(offsetof(ImDrawVert, uv)));
  glEnableVertexAttribArray(2);
  glVertexAttribPointer(2, 4, GL_UNSIGNED_BYTE, GL_TRUE, stride, offset(offsetof(ImDrawVert, col)));
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  if (previous != nullptr) ImGui::SetCurrentContext(previous);
}

Overlay::~Overlay() {
  glDeleteTextures(1, &font_tex_);
  const std::array<GLuint, 2> bufs{vbo_, ibo_};
  glDeleteBuffers(static_cast<GLsizei>(bufs.size()), bufs.data());
  glDeleteVertexArrays(1, &vao_);
  if (ImGui::GetCurrentContext() == imgui_) ImGui::SetCurrentContext(nullptr);
  ImGui::DestroyContext(imgui_);
}

OverlayResult Overlay::draw(const OverlayData& data, const SnapshotOptions& options, int width,
                            int height, const OverlayInput& input) {
  OverlayResult result;
  if ((!data.visible && !data.help) || width <= 0 || height <= 0) return result;
  ImGui::SetCurrentContext(imgui_);
  ImGuiIO& io = ImGui::GetIO();
  io.DisplaySize = ImVec2(static_cast<float>(width), static_cast<float>(height));
  io.DisplayFramebufferScale = ImVec2(1.0f, 1.0f);
  io.DeltaTime = std::max(input.dt_s, 1e-4f);
  io.MousePos = input.mouse_x >= 0.0f && input.mouse_y >= 0.0f
                    ? ImVec2(input.mouse_x, input.mouse_y)
                    : ImVec2(-FLT_MAX, -FLT_MAX);
  if (first_frame_ || (data.replay && !replay_shown_)) {
    // Auto-sized windows measure their contents on their first frame and show from the second:
    // lay out one throw-away frame (no input) when a panel appears, so that every picture is
    // complete.
    io.MousePos = ImVec2(-FLT_MAX, -FLT_MAX);
    io.MouseDown[0] = false;
    ImGui::NewFrame();
    (void)layout(data, options, width, height);
    ImGui::EndFrame();
    first_frame_ = false;
    io.MousePos = input.mouse_x >= 0.0f && input.mouse_y >= 0.0f
                      ? ImVec2(input.mouse_x, input.mouse_y)
                      : ImVec2(-FLT_MAX, -FLT_MAX);
  }
  replay_shown_ = data.replay;
  io.MouseDown[0] = input.mouse_down;
  ImGui::NewFrame();
  result = layout(data, options, width, height);
  result.wants_mouse = io.WantCaptureMouse;
  ImGui::Render();
  render_draw_data();
  return result;
}

OverlayResult Overlay::layout(const OverlayData& data, const SnapshotOptions& options, int width,
                              int height) {
  OverlayResult result;

  const ImGuiWindowFlags panel = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove |
                                 ImGuiWindowFlags_AlwaysAutoResize |
                                 ImGuiWindowFlags_NoSavedSettings |
                                 ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav;
  if (data.help) layout_help(panel, width, height);
  // H hides the panels; a replay's timeline stays (it is how the instructor finds the way).
  if (data.replay) layout_replay(data, panel, width, height, result);
  if (!data.visible) return result;
  if (!data.hands.empty()) layout_hands(data, panel, width);
  // Statistics, top left (above the replay's panel: at most down to its top).
  const float bottom = data.replay ? result.replay_bar[1] : static_cast<float>(height);
  ImGui::SetNextWindowPos(ImVec2(10.0f, 10.0f), ImGuiCond_Always);
  ImGui::SetNextWindowSizeConstraints(ImVec2(0.0f, 0.0f),
                                      ImVec2(0.3f * static_cast<float>(width), bottom - 20.0f));
  ImGui::SetNextWindowBgAlpha(0.55f);
  if (ImGui::Begin("Statistics", nullptr, panel)) {
    const OverlayText text = overlay_text(data);
    for (std::size_t i = 0; i < text.stats.size(); ++i) {
      if (i == 4) ImGui::Separator();  // the metrics
      if (i == 2 && data.haptic_rate_hz <= 0.0) {
        // ImGui's built-in font has no em dash: a hyphen in the picture, greyed out.
        ImGui::TextDisabled("haptics -%s%s%s", data.instruments != nullptr ? "  (" : "",
                            data.instruments != nullptr ? data.instruments : "",
                            data.instruments != nullptr ? ")" : "");
      } else {
        ImGui::TextUnformatted(text.stats[i].c_str());
      }
    }
    if (text.stats.size() > 4) ImGui::Separator();
    int view = 0;
    for (std::size_t i = 0; i < kViews.size(); ++i)
      if (kViews[i] == options.view) view = static_cast<int>(i);
    ImGui::SetNextItemWidth(110.0f);
    if (ImGui::Combo("view", &view, "visual\0collision\0mechanical\0")) {
      result.view = kViews[static_cast<std::size_t>(std::clamp(view, 0, 2))];
    }
    int level = options.tessellation;
    ImGui::SetNextItemWidth(110.0f);
    if (ImGui::SliderInt("tessellation", &level, 1, 16)) result.tessellation = level;
    const ImVec2 pos = ImGui::GetWindowPos();
    const ImVec2 size = ImGui::GetWindowSize();
    result.stats_rect = {pos.x, pos.y, pos.x + size.x, pos.y + size.y};
  }
  ImGui::End();
  if (data.replay) layout_debrief(data, panel, width, bottom, result);
  return result;
}

void Overlay::layout_replay(const OverlayData& data, int panel, int width, int height,
                            OverlayResult& result) {
  const float margin = 10.0f;
  ImGui::SetNextWindowPos(ImVec2(margin, static_cast<float>(height) - margin), ImGuiCond_Always,
                          ImVec2(0.0f, 1.0f));
  ImGui::SetNextWindowSize(ImVec2(static_cast<float>(width) - 2.0f * margin, 0.0f),
                           ImGuiCond_Always);
  ImGui::SetNextWindowBgAlpha(0.55f);
  const ImGuiWindowFlags bar = panel & ~ImGuiWindowFlags_AlwaysAutoResize;
  if (ImGui::Begin("Replay", nullptr, bar)) {
    if (!data.branch.empty()) draw_branch_band(data.branch);
    draw_timeline(data, overlay_text(data).errors);
    if (ImGui::Button(data.paused ? " Play  " : " Pause ")) result.toggle_pause = true;
    result.pause_button = last_item_rect();
    ImGui::SameLine();
    const std::string label = overlay_text(data).timeline;
    const double duration = std::max(data.replay_duration_s, 1e-6);
    auto position =
        static_cast<float>(std::clamp(data.replay_position_s, 0.0, duration) / duration);
    ImGui::SetNextItemWidth(-1.0f);
    if (ImGui::SliderFloat("##timeline", &position, 0.0f, 1.0f, label.c_str(),
                           ImGuiSliderFlags_AlwaysClamp)) {
      result.seek_s = static_cast<double>(position) * duration;
    }
    result.timeline = last_item_rect();
    const ImVec2 pos = ImGui::GetWindowPos();
    const ImVec2 size = ImGui::GetWindowSize();
    result.replay_bar = {pos.x, pos.y, pos.x + size.x, pos.y + size.y};
  }
  ImGui::End();
}

// The debrief, top right: at most a quarter of the view's width, and never down over the replay's
// panel (what does not fit scrolls).
void Overlay::layout_debrief(const OverlayData& data, int panel, int width, float bottom,
                             OverlayResult& result) {
  const float w = 0.25f * static_cast<float>(width) - 10.0f;
  ImGui::SetNextWindowPos(ImVec2(static_cast<float>(width) - 10.0f, 10.0f), ImGuiCond_Always,
                          ImVec2(1.0f, 0.0f));
  ImGui::SetNextWindowSize(ImVec2(w, 0.0f), ImGuiCond_Always);
  ImGui::SetNextWindowSizeConstraints(ImVec2(w, 0.0f), ImVec2(w, std::max(bottom - 20.0f, 40.0f)));
  ImGui::SetNextWindowBgAlpha(0.6f);
  const ImGuiWindowFlags flags = (panel & ~ImGuiWindowFlags_AlwaysAutoResize);
  if (ImGui::Begin("Debrief", nullptr, flags)) {
    if (data.debrief) {
      debrief_contents(*data.debrief, false);
    } else {
      ImGui::PushTextWrapPos(0.0f);
      ImGui::TextDisabled("%s", data.timeline.done ? "this recording is scored by no rubric"
                                                   : "assessing the recording ...");
      ImGui::PopTextWrapPos();
    }
    const ImVec2 pos = ImGui::GetWindowPos();
    const ImVec2 size = ImGui::GetWindowSize();
    result.debrief = {pos.x, pos.y, pos.x + size.x, pos.y + size.y};
  }
  ImGui::End();
}

void Overlay::layout_hands(const OverlayData& data, int panel, int width) {
  ImGui::SetNextWindowPos(ImVec2(static_cast<float>(width) - 10.0f, 10.0f), ImGuiCond_Always,
                          ImVec2(1.0f, 0.0f));
  ImGui::SetNextWindowBgAlpha(0.6f);
  if (ImGui::Begin("Instruments", nullptr, panel)) {
    const OverlayText text = overlay_text(data);
    for (std::size_t i = 0; i < text.hands.size(); ++i) {
      if (i < data.hands.size() && data.hands[i].active)
        ImGui::TextColored(ImVec4(0.45f, 1.0f, 0.55f, 1.0f), "%s", text.hands[i].c_str());
      else
        ImGui::TextUnformatted(text.hands[i].c_str());
    }
    ImGui::TextDisabled("H: controls");
  }
  ImGui::End();
}

void Overlay::layout_help(int panel, int width, int height) {
  ImGui::SetNextWindowPos(
      ImVec2(0.5f * static_cast<float>(width), 0.5f * static_cast<float>(height)), ImGuiCond_Always,
      ImVec2(0.5f, 0.5f));
  ImGui::SetNextWindowBgAlpha(0.8f);
  if (ImGui::Begin("Controls", nullptr, panel)) {
    const std::vector<std::string>& lines = overlay_help_lines();
    ImGui::TextColored(ImVec4(1.0f, 0.9f, 0.5f, 1.0f), "%s", lines.front().c_str());
    ImGui::Separator();
    for (std::size_t i = 1; i < lines.size(); ++i) ImGui::TextUnformatted(lines[i].c_str());
  }
  ImGui::End();
}

void Overlay::render_draw_data() {
  const ImDrawData* dd = ImGui::GetDrawData();
  if (dd == nullptr || dd->CmdListsCount == 0) return;
  const float w = dd->DisplaySize.x;
  const float h = dd->DisplaySize.y;
  glEnable(GL_BLEND);
  glBlendEquation(GL_FUNC_ADD);
  // Colour blends over the picture; alpha (the coverage read back by tests) takes the maximum.
  glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  glDisable(GL_CULL_FACE);
  glDisable(GL_DEPTH_TEST);
  glEnable(GL_SCISSOR_TEST);
  glUseProgram(program_->id());
  glUniform2f(program_->uniform("u_size"), w, h);
  glUniform1i(program_->uniform("u_font"), 0);
  glActiveTexture(GL_TEXTURE0);
  glBindVertexArray(vao_);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_);
  const ImVec2 origin = dd->DisplayPos;
  for (int n = 0; n < dd->CmdListsCount; ++n) {
    const ImDrawList* list = dd->CmdLists[n];
    glBufferData(
        GL_ARRAY_BUFFER,
        static_cast<GLsizeiptr>(list->VtxBuffer.Size) * static_cast<GLsizeiptr>(sizeof(ImDrawVert)),
        list->VtxBuffer.Data, GL_STREAM_DRAW);
    glBufferData(
        GL_ELEMENT_ARRAY_BUFFER,
        static_cast<GLsizeiptr>(list->IdxBuffer.Size) * static_cast<GLsizeiptr>(sizeof(ImDrawIdx)),
        list->IdxBuffer.Data, GL_STREAM_DRAW);
    for (int c = 0; c < list->CmdBuffer.Size; ++c) {
      const ImDrawCmd& cmd = list->CmdBuffer[c];
      if (cmd.UserCallback != nullptr) continue;  // the overlay adds none
      const float x0 = cmd.ClipRect.x - origin.x;
      const float y0 = cmd.ClipRect.y - origin.y;
      const float x1 = cmd.ClipRect.z - origin.x;
      const float y1 = cmd.ClipRect.w - origin.y;
      if (x1 <= x0 || y1 <= y0) continue;
      // GL's scissor origin is the bottom left.
      glScissor(static_cast<GLint>(x0), static_cast<GLint>(h - y1), static_cast<GLsizei>(x1 - x0),
                static_cast<GLsizei>(y1 - y0));
      glBindTexture(GL_TEXTURE_2D, gl_texture(cmd.GetTexID()));
      glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(cmd.ElemCount),
                     sizeof(ImDrawIdx) == 2 ? GL_UNSIGNED_SHORT : GL_UNSIGNED_INT,
                     reinterpret_cast<const void*>(
                         static_cast<std::uintptr_t>(cmd.IdxOffset * sizeof(ImDrawIdx))));
    }
  }
  glBindTexture(GL_TEXTURE_2D, 0);
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  glUseProgram(0);
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_BLEND);
  glEnable(GL_DEPTH_TEST);
}

}  // namespace serosa::render

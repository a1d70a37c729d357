// What the trainee window showed, frame by frame, as JSON lines (`serosa run --view-log FILE`):
// where each instrument's tip, jaw tips and the middle of its jaws, the guide (the planned cut)
// and each organ group were drawn, in the window's pixels (origin top left) with their depth
// along the view, m; which hand the mouse steers, the jaws' opening and the tip's distance to
// tissue as the overlay shows them. For studies of where trainees looked and aimed, and for the
// tests that drive the window by hand as a person does: they aim by what the window draws.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "render/render_frame.h"

namespace serosa::window {

class ViewLog {
 public:
  /// Opens (truncates) `file`; `tools` are the scene's tool names (scene order). Throws
  /// InputError naming the file when it cannot be written.
  ViewLog(const std::filesystem::path& file, std::vector<std::string> tools);

  /// One line for the frame drawn at wall time `wall_s` (s since the session began) into a
  /// width x height window, the mouse steering `active_hand` (-1: none). Flushed: a reader
  /// following the file sees every frame as it is drawn.
  void write(const render::RenderFrame& frame, int width, int height, double wall_s,
             int active_hand);

 private:
  std::filesystem::path m_file;
  std::vector<std::string> m_tools;
  std::ofstream m_out;
};

}  // namespace serosa::window

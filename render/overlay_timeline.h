// The replay panel's metric timeline (render/overlay.cpp draws it inside that panel): the tools'
// force on the tissue over the recording as a plot the width of the panel, the errors as red
// ticks at their times, the playback position as a white one, and the errors line under it.
#pragma once

#include <string>

#include "render/render_frame.h"

namespace serosa::render {

/// Lays out the timeline in the current ImGui window (between its Begin and End).
void draw_timeline(const OverlayData& data, const std::string& errors_line);

}  // namespace serosa::render

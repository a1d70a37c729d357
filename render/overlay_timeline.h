// The replay panel's timeline (render/overlay.cpp draws it inside that panel): the tools' force on
// the tissue over the recording as a plot the width of the panel, the errors as red ticks at
// their times, the playback position as a white one; under it the procedure's steps as a row of
// segments (name and instrument, where each began and ended; the steps never done listed after),
// then the errors line. Above it all, when the instructor has taken over, the branch's band.
#pragma once

#include <string>

#include "render/render_frame.h"

namespace serosa::render {

/// Lays out the timeline in the current ImGui window (between its Begin and End).
void draw_timeline(const OverlayData& data, const std::string& errors_line);

/// A band across the current ImGui window saying who drives what in a branch.
void draw_branch_band(const std::string& text);

}  // namespace serosa::render

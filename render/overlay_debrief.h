// The debrief's contents (render/session_summary.h) inside the current ImGui window: the title, a
// banner of the verdict's colour, the score and the GOALS domains, why it failed and what to work
// on, the procedure's steps, then the rubric's metrics in one collapsed section per domain. The
// trainee's end-of-session panel and the instructor's replay panel both lay it out this way.
#pragma once

#include "render/session_summary.h"

namespace serosa::render {

/// Between ImGui's Begin and End; `with_way_out`: the trainee's screen (how to leave).
void debrief_contents(const SessionSummary& s, bool with_way_out);

}  // namespace serosa::render

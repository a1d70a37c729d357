// The software renderer's worker threads (Mesa's llvmpipe) give way to the solver: on two cores
// they would otherwise take both whenever a frame is drawn, and the solver's step, due every 5 ms,
// waited behind them. Raising their nice value needs no privilege and changes no picture.
#pragma once

namespace serosa::render {

/// Lowers the priority (nice `nice`, 0..19) of this process's threads whose name starts with
/// "llvmpipe" (Mesa names its rasterizer threads so); call after the GL context exists. Returns
/// how many it lowered (0 on a GPU driver).
int lower_software_renderer_threads(int nice);

}  // namespace serosa::render

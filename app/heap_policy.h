// The process's heap policy, set once at start-up before any stage allocates.
#pragma once

namespace serosa::app {

/// Keeps memory the process frees in its heap instead of handing it back to the kernel, and
/// serves large blocks from that heap rather than from fresh mappings. Why: after a cut the FEM
/// step re-sizes matrices of a few megabytes (the system, the refresh's copy, the patch); served
/// from fresh mappings, every page faulted on first touch, about a millisecond of a 5 ms step on
/// this VM. Kept, the step after a cut reuses pages it already touched. The price is that the
/// resident size stays at its peak (tens of megabytes for the default scene).
void keep_freed_memory();

}  // namespace serosa::app

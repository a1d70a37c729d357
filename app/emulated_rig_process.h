// The emulated rig (device "rig-emulated:FILE") is libusb's own code path against a USB device
// umockdev emulates in this process. umockdev's preload library must be in the process from its
// start, so a command whose scene asks for it runs itself again under umockdev-wrapper, with the
// same command line, before it does anything else.
#pragma once

#include "engine/scene/scene.h"

namespace serosa::app {

/// Whether the scene's instruments are driven by a rig this process emulates.
[[nodiscard]] bool emulates_rig(const Scene& scene);

/// When `scene` emulates the rig and the preload is not in this process, re-executes this
/// process (its /proc/self/cmdline) under umockdev-wrapper and does not return; otherwise
/// returns at once. Throws std::runtime_error when umockdev-wrapper cannot be run.
void run_under_umockdev_if_rig_emulated(const Scene& scene);

}  // namespace serosa::app

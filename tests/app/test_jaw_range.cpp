// One jaw range per instrument (engine/jaw_range.h): the shipped scripts open no instrument wider
// than its range and, over them all, each kind of instrument opens exactly that wide; the mouse
// opens a handle's instrument to it (haptics_stage.cpp), and the rig's handles are held to it.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>

#include "app_test_util.h"
#include "engine/input_error.h"
#include "engine/jaw_range.h"
#include "engine/scene/scene.h"
#include "engine/scene/tool_path.h"

namespace serosa::app {
namespace {

using testing::source;

TEST(JawRange, TheScriptsOpenEachInstrumentExactlyAsWideAsItsRange) {
  std::map<ToolKind, double> widest;
  int scenes = 0;
  for (const auto& [file, scene] : testing::shipped_scenes()) {
    ++scenes;
    for (const Tool& t : scene.tools) {
      if (t.device.script.empty()) continue;
      const ToolPath path = read_tool_path(t.device.script);
      const auto k = path.index_of(t.name);
      if (!k) continue;
      for (const ToolState& s : path.samples[*k]) {
        EXPECT_LE(s.jaw_rad, max_jaw_rad(t.kind) + 1e-12)
            << file << " " << t.name << " at " << s.time_s << " s";
        widest[t.kind] = std::max(widest[t.kind], s.jaw_rad);
      }
    }
  }
  EXPECT_GE(scenes, 8);
  for (const ToolKind kind :
       {ToolKind::kScissors, ToolKind::kGrasper, ToolKind::kClipApplier, ToolKind::kEndoloop}) {
    ASSERT_TRUE(widest.count(kind)) << static_cast<int>(kind);
    EXPECT_DOUBLE_EQ(widest[kind], max_jaw_rad(kind)) << static_cast<int>(kind);
  }
}

}  // namespace
}  // namespace serosa::app

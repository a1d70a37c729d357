#include "replay/recorded_scene.h"

#include "engine/input_error.h"
#include "engine/scene/scene.h"

namespace serosa::replay {

Scene recorded_scene(const recording::Recording& rec, const std::string& file) {
  const std::string scene_path = rec.header.get("scene_path");
  const std::string scene_text = rec.header.get("scene_text");
  if (scene_path.empty() || scene_text.empty())
    throw InputError(file, 0, "the header holds no scene", "scene_path and scene_text");
  Scene scene = parse_scene_text(scene_text, scene_path);
  for (std::size_t s = 0; s < rec.inputs.size(); ++s)
    if (rec.inputs[s].size() != scene.tools.size())
      throw InputError(file, 0,
                       "step " + std::to_string(s) + " records " +
                           std::to_string(rec.inputs[s].size()) + " tools, the scene has " +
                           std::to_string(scene.tools.size()));
  return scene;
}

}  // namespace serosa::replay

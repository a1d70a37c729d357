// Tissue materials (no GL): a colour and a specular look per visual group, and the wound.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>

#include "render/render_frame.h"

namespace serosa::render {

/// How a surface looks under the endoscope light. Colours are sRGB in [0, 1].
struct Material {
  std::array<float, 3> color{0.8f, 0.8f, 0.8f};
  float specular = 0.35f;  ///< strength of the wet highlight, [0, 1]
};

/// The material of a named tissue: "appendix" (pink), "mesoappendix" (yellowish fat), "cecum"
/// (darker pink), "liver" (red-brown), "gallbladder" (green), "fat", "peritoneum", "colon",
/// "bowel"/"ileum" ...; case-sensitive. Returns false for an unknown name.
bool named_material(std::string_view name, Material& out);

/// The material of visual group `group`: by its name when frame.group_names names it and the name
/// is known, else a fixed palette colour chosen by the group id (tissue-like, never the wound's).
[[nodiscard]] Material group_material(const RenderFrame& frame, std::uint16_t group);

/// The material of the scenery around the organs (render/scenery.h): the posterior wall's wet
/// peritoneum a pinkish red, small bowel pinker and paler, mesenteric fat yellow.
[[nodiscard]] Material scenery_material(SceneryMaterial m);

/// The wound: faces made by a cut, a dark, glossy red distinct from every tissue colour.
[[nodiscard]] Material wound_material();
/// Tissue a hook coagulated: a dry, pale tan, matt.
[[nodiscard]] Material coagulated_material();

}  // namespace serosa::render

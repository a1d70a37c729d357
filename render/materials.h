// Tissue materials (no GL): a colour and a specular look per visual group, and the wound.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>

#include "render/render_frame.h"

namespace serosa::render {

/// What kind of surface a triangle is: its outside, a face a cut made, or tissue a hook burnt.
enum class SurfaceKind : std::uint8_t { kOutside = 0, kCut = 1, kCharred = 2 };

/// How a surface looks under the endoscope light (render/tissue_pattern.h lays the pattern out).
/// Colours are sRGB in [0, 1]; the other fields are strengths in [0, 1].
struct Material {
  std::array<float, 3> color{0.8f, 0.8f, 0.8f};
  float specular = 0.35f;  ///< strength of the wet highlight
  float vessels = 0.5f;    ///< how strongly the serosa's vessel network shows
  float lobules = 0.0f;    ///< fat lobules: 1 for fat, 0 for smooth serosa
  float mottle = 0.5f;     ///< colour variation and fine relief of the surface
  SurfaceKind kind = SurfaceKind::kOutside;
  /// The cecum's and colon's taeniae: three pale longitudinal bands of muscle, converging where
  /// the appendix leaves (RenderFrame::taenia_axis)
  bool taenia = false;
};

/// The material of a named tissue: "appendix" (an inflamed appendix: red, many vessels),
/// "mesoappendix" and "fat" (yellow lobular fat), "artery" (a dark red-violet vessel), "cecum"
/// (deeper pink), "liver" (red-brown), "gallbladder" (green), "peritoneum", "colon",
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
/// Tissue a hook coagulated: a dry, pale tan, matt, with charred specks.
[[nodiscard]] Material coagulated_material();

/// The two RGBA8 texels a triangle's material takes in the renderer's material buffer: rgb the
/// colour and a the specular strength; then vessels, lobules, mottle and the kind (0 outside, 64
/// outside with taeniae, 128 cut, 255 charred).
[[nodiscard]] std::array<std::uint8_t, 8> pack_material(const Material& m);

}  // namespace serosa::render

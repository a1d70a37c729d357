// Tissue materials (see materials.h). Colours were picked by eye against laparoscopic photographs:
// serosa is pale pink and glossy, fat pale yellow, the cecum a deeper pink, cut tissue dark red.
#include "render/materials.h"

#include <algorithm>
#include <cmath>

namespace serosa::render {
namespace {

struct Named {
  std::string_view name;
  Material material;
};

// {colour, specular, vessels, lobules, mottle}: serosa carries a vessel network, fat is lobular
// with a brighter highlight, the inflamed appendix is redder with more vessels (hyperaemia), the
// cecum and colon carry their taeniae.
constexpr std::array<Named, 12> kNamed{{
    {"appendix", {{0.90f, 0.50f, 0.48f}, 0.55f, 0.85f, 0.0f, 0.6f}},
    {"mesoappendix", {{0.94f, 0.80f, 0.50f}, 0.65f, 0.45f, 1.0f, 0.5f}},
    {"artery", {{0.62f, 0.20f, 0.28f}, 0.60f, 0.0f, 0.0f, 0.3f}},
    {"cecum", {{0.84f, 0.52f, 0.52f}, 0.50f, 0.60f, 0.0f, 0.55f, SurfaceKind::kOutside, true}},
    {"colon", {{0.84f, 0.56f, 0.54f}, 0.50f, 0.55f, 0.0f, 0.55f, SurfaceKind::kOutside, true}},
    {"bowel", {{0.90f, 0.60f, 0.58f}, 0.50f, 0.55f, 0.0f, 0.5f}},
    {"ileum", {{0.90f, 0.60f, 0.58f}, 0.50f, 0.55f, 0.0f, 0.5f}},
    {"liver", {{0.55f, 0.20f, 0.16f}, 0.50f, 0.15f, 0.0f, 0.7f}},
    {"gallbladder", {{0.45f, 0.58f, 0.32f}, 0.55f, 0.45f, 0.0f, 0.4f}},
    {"fat", {{0.94f, 0.80f, 0.50f}, 0.65f, 0.45f, 1.0f, 0.5f}},
    {"peritoneum", {{0.88f, 0.72f, 0.70f}, 0.45f, 0.50f, 0.0f, 0.5f}},
    {"stomach", {{0.88f, 0.58f, 0.55f}, 0.45f, 0.55f, 0.0f, 0.5f}},
}};

// Used for unnamed groups, by id: soft tissue-like hues that stay far from the wound's red.
constexpr std::array<std::array<float, 3>, 8> kPalette{{
    {0.93f, 0.62f, 0.62f},  // pink
    {0.95f, 0.84f, 0.50f},  // fat yellow
    {0.80f, 0.45f, 0.50f},  // dark pink
    {0.70f, 0.74f, 0.90f},  // bluish (vessel-like)
    {0.60f, 0.80f, 0.60f},  // pale green
    {0.85f, 0.70f, 0.90f},  // lilac
    {0.90f, 0.75f, 0.60f},  // tan
    {0.70f, 0.88f, 0.88f},  // pale cyan
}};

}  // namespace

bool named_material(std::string_view name, Material& out) {
  for (const Named& n : kNamed) {
    if (n.name == name) {
      out = n.material;
      return true;
    }
  }
  return false;
}

Material group_material(const RenderFrame& frame, std::uint16_t group) {
  Material m;
  if (group < frame.group_names.size() && named_material(frame.group_names[group], m)) return m;
  // Gmsh physical tags usually start at 1: group 1 gets the first palette colour.
  const std::size_t idx = (static_cast<std::size_t>(group) + kPalette.size() - 1) % kPalette.size();
  m.color = kPalette[idx];
  m.specular = 0.4f;
  return m;
}

Material scenery_material(SceneryMaterial m) {
  switch (m) {
    case SceneryMaterial::kPeritoneum:
      return {{0.80f, 0.42f, 0.40f}, 0.50f, 0.70f, 0.0f, 0.6f};
    case SceneryMaterial::kBowel:
      return {{0.93f, 0.64f, 0.62f}, 0.55f, 0.55f, 0.0f, 0.5f};
    case SceneryMaterial::kFat:
      return {{0.96f, 0.83f, 0.46f}, 0.40f, 0.30f, 1.0f, 0.5f};
  }
  return {};
}

Material wound_material() {
  return {{0.45f, 0.04f, 0.06f}, 0.75f, 0.0f, 0.0f, 0.8f, SurfaceKind::kCut};
}
Material coagulated_material() {
  return {{0.62f, 0.52f, 0.40f}, 0.1f, 0.0f, 0.0f, 0.8f, SurfaceKind::kCharred};
}

std::array<std::uint8_t, 8> pack_material(const Material& m) {
  const auto byte = [](float v) {
    return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
  };
  const std::uint8_t kind = m.kind == SurfaceKind::kCut       ? 128
                            : m.kind == SurfaceKind::kCharred ? 255
                            : m.taenia                        ? 64
                                                              : 0;
  return {byte(m.color[0]), byte(m.color[1]), byte(m.color[2]), byte(m.specular),
          byte(m.vessels),  byte(m.lobules),  byte(m.mottle),   kind};
}

}  // namespace serosa::render

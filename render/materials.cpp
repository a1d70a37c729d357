// Tissue materials (see materials.h). Colours were picked by eye against laparoscopic photographs:
// serosa is pale pink and glossy, fat pale yellow, the cecum a deeper pink, cut tissue dark red.
#include "render/materials.h"

namespace serosa::render {
namespace {

struct Named {
  std::string_view name;
  Material material;
};

constexpr std::array<Named, 11> kNamed{{
    {"appendix", {{0.93f, 0.62f, 0.62f}, 0.45f}},
    {"mesoappendix", {{0.95f, 0.84f, 0.50f}, 0.30f}},
    {"cecum", {{0.80f, 0.45f, 0.50f}, 0.40f}},
    {"colon", {{0.82f, 0.52f, 0.52f}, 0.40f}},
    {"bowel", {{0.90f, 0.60f, 0.58f}, 0.45f}},
    {"ileum", {{0.90f, 0.60f, 0.58f}, 0.45f}},
    {"liver", {{0.55f, 0.20f, 0.16f}, 0.50f}},
    {"gallbladder", {{0.45f, 0.58f, 0.32f}, 0.55f}},
    {"fat", {{0.95f, 0.86f, 0.55f}, 0.30f}},
    {"peritoneum", {{0.88f, 0.72f, 0.70f}, 0.40f}},
    {"stomach", {{0.88f, 0.58f, 0.55f}, 0.40f}},
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
      return {{0.80f, 0.42f, 0.40f}, 0.50f};
    case SceneryMaterial::kBowel:
      return {{0.93f, 0.64f, 0.62f}, 0.55f};
    case SceneryMaterial::kFat:
      return {{0.96f, 0.83f, 0.46f}, 0.35f};
  }
  return {};
}

Material wound_material() { return {{0.45f, 0.04f, 0.06f}, 0.75f}; }
Material coagulated_material() { return {{0.62f, 0.52f, 0.40f}, 0.1f}; }

}  // namespace serosa::render

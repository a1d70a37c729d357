#include "batch/run_fingerprint.h"

#include <cstdio>

#include "engine/fnv1a.h"

namespace serosa::batch {

std::string run_fingerprint(const BatchRun& r, const std::string& binary) {
  Fnv1a f;
  f.text(binary);
  f.text(r.scene.string());
  f.file(r.scene);
  if (r.path)
    f.file(*r.path);
  else
    f.text("-");
  f.text(r.steps ? std::to_string(*r.steps) : std::string("-"));
  for (const SceneOverride& o : r.overrides) {
    f.text(o.key);
    f.text(o.value);
  }
  f.text(r.seed ? std::to_string(*r.seed) : std::string("-"));
  f.bytes(&r.perturb_m, sizeof r.perturb_m);
  f.text(r.golden ? r.golden->string() : std::string("-"));
  f.text(r.strict ? "strict" : "lenient");
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(f.h));
  return hex;
}

}  // namespace serosa::batch

#include "app/version.h"

namespace serosa::app {

std::string_view version_string() noexcept {
#if defined(SEROSA_HAVE_CUDA)
  return "serosa 0.1.0 (CUDA on)";
#else
  return "serosa 0.1.0 (CUDA off)";
#endif
}

}  // namespace serosa::app

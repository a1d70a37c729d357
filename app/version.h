#pragma once
#include <string_view>
namespace serosa::app {
/// "serosa 0.1.0 (CUDA on|off)": printed by --version and written into every report.
[[nodiscard]] std::string_view version_string() noexcept;
}  // namespace serosa::app

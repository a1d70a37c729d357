#pragma once
#include <string>
#include <string_view>
namespace serosa::app {
/// "serosa 0.1.0 (CUDA on|off)": printed by --version and written into every report.
[[nodiscard]] std::string_view version_string() noexcept;
/// 16 hex digits naming this executable's bytes (FNV-1a of /proc/self/exe): two runs share it
/// only when they ran the same binary. "unknown" when it cannot be read.
[[nodiscard]] std::string binary_id();
}  // namespace serosa::app

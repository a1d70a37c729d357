// Where the tests find the checkout's files and write their own. The paths are compiled into
// tests/support/test_paths.cpp alone, so every other test source compiles to the same object in
// any clone of the repository (and a compiler cache shares it between clones).
#pragma once

namespace serosa::test_paths {

[[nodiscard]] const char* source_dir();  ///< the repository root, absolute
[[nodiscard]] const char* binary_dir();  ///< the build folder (CMake's PROJECT_BINARY_DIR)
[[nodiscard]] const char* test_data();   ///< tests/data, absolute

}  // namespace serosa::test_paths

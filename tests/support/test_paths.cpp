#include "support/test_paths.h"

namespace serosa::test_paths {

const char* source_dir() { return SEROSA_SOURCE_DIR; }
const char* binary_dir() { return SEROSA_BINARY_DIR; }
const char* test_data() { return SEROSA_TEST_DATA; }

}  // namespace serosa::test_paths

#include "app/heap_policy.h"

#include <malloc.h>

namespace serosa::app {

void keep_freed_memory() {
  constexpr int kNever = 1 << 30;  // 1 GiB: above any block the simulator allocates
  mallopt(M_MMAP_THRESHOLD, kNever);
  mallopt(M_TRIM_THRESHOLD, kNever);
}

}  // namespace serosa::app

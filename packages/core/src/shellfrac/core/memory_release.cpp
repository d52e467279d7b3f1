#include "shellfrac/core/memory_release.hpp"

#include <cstdlib>  // defines __GLIBC__ under glibc

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace shellfrac {

void release_freed_memory_promptly() {
#if defined(__GLIBC__)
  mallopt(M_MMAP_THRESHOLD, own_mapping_bytes);  // a fixed threshold: glibc no longer raises it
#endif
}

}  // namespace shellfrac

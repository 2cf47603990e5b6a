#include "allocator_tuning.hpp"

#include <cstdlib>  // defines __GLIBC__ with the GNU C library

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace l2s::cli {

void keep_large_buffers() {
#if defined(__GLIBC__)
  // 32 MiB is the largest threshold glibc accepts on 64-bit (half its heap
  // size): blocks up to it come from the heap and return to it when freed.
  constexpr int kMapThreshold = 32 << 20;
  // The heap's top is given back only beyond this much, so a frame's freed
  // buffers stay for the next (30 frames of a 1280x960 rig peaked at 253 MB,
  // 220 MB without this).
  constexpr int kTrimThreshold = 256 << 20;
  mallopt(M_MMAP_THRESHOLD, kMapThreshold);
  mallopt(M_TRIM_THRESHOLD, kTrimThreshold);
#endif
}

}  // namespace l2s::cli

#pragma once
// How the l2s tool asks the C library's allocator to treat its per-frame buffers.

namespace l2s::cli {

/// Keeps freed image-sized buffers in the process for the next frame instead
/// of returning them to the kernel (glibc; a no-op elsewhere). Each frame
/// allocates and frees the same images, disparity maps and clouds (1-30 MB
/// each); by default glibc maps every block above its threshold afresh and
/// unmaps it on free, so the kernel clears its pages again every frame: on a
/// 30-frame calibration of a 1280x960 rig that was 1.5 s of 9 s of CPU.
/// Process-wide, so it is the tool's choice, not the library's.
void keep_large_buffers();

}  // namespace l2s::cli

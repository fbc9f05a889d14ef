// frame_memory.hpp — the allocator policy of processes that handle one image-sized buffer after
// another: rendering (`synth`), a cell's frame loop (`cell-exec`) and `vobench track`.
//
// glibc hands a block above its mmap threshold to mmap and returns the top of the heap to the system
// once more than its trim threshold is free; both thresholds start low (128 KiB) and move with what
// the process freed last. Frame-sized buffers (a Kinect v2 frame: 6 MB colour, 4 MB registered
// depth, their decoded copies) were then faulted in page by page on every frame, or not, depending on
// the order of earlier allocations. Raised once, first thing in main(), the freed blocks stay on the
// heap and the next frame reuses them. Measured on this project's 2-core VM: the demo's Kinect v2
// cells read a frame in 42–51 ms before, 19–25 ms after (medians per cell, the two builds alternated
// twice; the same trajectories, peak RSS within 2 %); `synth`, 40 Kinect v1 frames: 72,346 page
// faults and 4.69 s of CPU before, 14,193 and 4.28 s after. Nothing computed changes.
#pragma once

#ifdef __GLIBC__
#include <malloc.h>
#endif

namespace vobench {

// glibc's mmap threshold to its 64-bit cap (32 MiB) and its trim threshold to 1 GiB. Call first
// thing in main(), before any frame is allocated; a no-op where the C library is not glibc.
inline void keep_frame_buffers_allocated() {
#ifdef __GLIBC__
    mallopt(M_MMAP_THRESHOLD, 32 << 20);
    mallopt(M_TRIM_THRESHOLD, 1 << 30);
#endif
}

}  // namespace vobench

#pragma once
// Process-wide memory policy for frame streams.

namespace uwgrasp {

// Keeps the memory that large buffers (a frame's clouds, neighbour lists, images) free in the
// heap for the next frame, instead of returning it to the operating system and faulting it in
// again page by page: glibc hands buffers above its mmap threshold back on free, and trims its
// heap's freed top. A fresh page costs 0.1-12 us depending on the machine (on the 2-core VM of
// docs/benchmarks.md 12 us one day, when a 640x480 frame's buffers cost more than its
// arithmetic, and 1.6 us another). Call once at start-up in a
// program that processes more than one frame; memory use then stays at its peak. Returns
// whether the policy is in force: false where the C library is not glibc (a no-op there).
bool keep_freed_memory();

}  // namespace uwgrasp

#pragma once
// How the process's allocator treats the memory edgevio frees.

namespace edgevio {

/// Makes freed memory stay with the process for its next allocations:
/// blocks up to 64 MiB come from the heap and freed memory is handed back to
/// the system only above 256 MiB of free space. Per frame the pipeline
/// allocates and frees the same large buffers (distance-transform scratch,
/// the window's normal equations, image levels) on four threads; with
/// glibc's defaults freed memory goes back to the system and every reuse
/// page-faults it in again (docs/performance.md). Results are unchanged.
/// Call once at the start of a program, before its threads start. Returns
/// false where the allocator has no such settings (not glibc, or replaced
/// by a sanitizer's).
bool keepFreedMemory();

}  // namespace edgevio

#pragma once
// How the process's allocator treats memory that episodes free.

namespace freeplay {

/// Keeps the memory a finished episode frees for the next one instead of handing it back to the system: glibc's
/// mmap threshold and trim threshold are fixed high, so the rasters, MuJoCo data and grids of each new episode reuse
/// pages already mapped rather than faulting fresh zeroed ones in (a process-wide setting; call it once at start).
/// The peak memory stays that of the largest episodes; nothing else changes.
void keep_freed_memory_for_reuse();

}  // namespace freeplay

#pragma once
// The memory of this process: what the system counts (resident set) and what the heap holds; and
// the allocator setting that lets a long run's resident set follow its heap.

namespace adaptive_lego_loam {

// Resident set size now and at its peak (MB), from /proc/self/status.
double resident_memory_mb();
double peak_resident_memory_mb();
// Bytes the program holds on the heap (MB), from the allocator (glibc's mallinfo2).
double heap_in_use_mb();

// Large blocks (256 KiB and up: scan clouds, voxel tables, KD-trees, a candidate's map) are
// mapped on their own and go back to the system when freed, and free memory at the heap's top is
// trimmed past 256 KiB. glibc otherwise raises its mapping threshold after the first large free
// and keeps such blocks in the heap for good, where the short-lived ones of loop closure leave
// holes: a run's resident set would grow with its largest transient buffers, not with what it
// keeps. The price is a page fault for every page of such a block each time one is allocated
// (a few ms a scan with the HDL-64E): processes without a growing map (image_projection,
// feature_association, transform_fusion) do without it. Call once at start (a process-wide
// setting).
void return_large_blocks_to_system();

}  // namespace adaptive_lego_loam

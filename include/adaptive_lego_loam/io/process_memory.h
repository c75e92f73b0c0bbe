#pragma once
// The memory of this process: what the system counts (resident set) and what the heap holds; and
// the allocator setting that lets a long run's resident set follow its heap.

namespace adaptive_lego_loam {

// Resident set size now and at its peak (MB), from /proc/self/status.
double resident_memory_mb();
double peak_resident_memory_mb();
// Bytes the program holds on the heap (MB), from the allocator (glibc's mallinfo2).
double heap_in_use_mb();

// Gives the heap's free pages back to the system (glibc's malloc_trim), wherever they lie in it.
// Called after every scan by what holds the map (run_sequence, map_optimization): glibc keeps
// freed memory in the heap for good, where the short-lived buffers of loop closure leave holes
// among the keyframes, and a run's resident set would grow with its largest transient buffers,
// not with what it keeps. The heap itself keeps glibc's defaults, so the per-scan buffers are
// reused without a page fault each (mapping every large block on its own costs a few ms a scan
// with the HDL-64E).
void return_free_memory_to_system();

}  // namespace adaptive_lego_loam

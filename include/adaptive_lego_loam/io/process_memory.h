#pragma once
// The memory of this process: what the system counts (resident set) and what the heap holds; and
// the trimming that lets a long run's resident set follow its heap.

namespace adaptive_lego_loam {

// Resident set size now and at its peak (MB), from /proc/self/status.
double resident_memory_mb();
double peak_resident_memory_mb();
// Bytes the program holds on the heap (MB), from the allocator (glibc's mallinfo2).
double heap_in_use_mb();

// Gives the heap's free pages back to the system (glibc's malloc_trim), wherever they lie in it.
void return_free_memory_to_system();

// What holds the map (run_sequence, map_optimization) calls after_scan() after every scan, and
// every `every_scans`-th call trims the heap. glibc keeps freed memory in the heap for good, where
// the short-lived buffers of loop closure leave holes among the keyframes, and a run's resident
// set would grow with its largest transient buffers, not with what it keeps. Trimming after every
// scan would cost milliseconds a scan with the HDL-64E: each scan's buffers would fault their pages
// in again. The allocator keeps glibc's defaults, which reuse the per-scan buffers.
class HeapTrimmer {
 public:
  explicit HeapTrimmer(int every_scans = 10) : every_scans_(every_scans) {}
  // True when it trimmed.
  bool after_scan();

 private:
  int every_scans_;
  int scans_ = 0;
};

}  // namespace adaptive_lego_loam

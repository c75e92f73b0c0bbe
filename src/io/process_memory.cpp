#include "adaptive_lego_loam/io/process_memory.h"

#include <malloc.h>

#include <fstream>
#include <sstream>
#include <string>

namespace adaptive_lego_loam {
namespace {

double status_field_mb(const char* field) {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind(field, 0) == 0) {
      std::istringstream in(line.substr(std::string(field).size()));
      double kilobytes = 0.0;
      in >> kilobytes;
      return kilobytes / 1024.0;
    }
  }
  return 0.0;
}

}  // namespace

double resident_memory_mb() {
  return status_field_mb("VmRSS:");
}

double peak_resident_memory_mb() {
  return status_field_mb("VmHWM:");
}

double heap_in_use_mb() {
  const struct mallinfo2 info = mallinfo2();
  return static_cast<double>(info.uordblks + info.hblkhd) / (1024.0 * 1024.0);
}

void return_free_memory_to_system() {
  malloc_trim(0);
}

bool HeapTrimmer::after_scan() {
  if (++scans_ < every_scans_) return false;
  scans_ = 0;
  return_free_memory_to_system();
  return true;
}

}  // namespace adaptive_lego_loam

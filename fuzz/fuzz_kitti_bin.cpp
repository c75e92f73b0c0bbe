// KITTI .bin scans (parse_kitti_bin): the input is the file. IoError is the answer to a file
// whose size is not a whole number of points.

#include "adaptive_lego_loam/io/io_error.h"
#include "adaptive_lego_loam/io/scan_files.h"
#include "fuzz_support.h"

using namespace adaptive_lego_loam;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  try {
    const Scan scan = parse_kitti_bin(bytes, "fuzz.bin");
    fuzz::check(scan.points.size() * 16 == size, "a KITTI scan has 16 bytes a point");
  } catch (const IoError&) {
  }
  return 0;
}

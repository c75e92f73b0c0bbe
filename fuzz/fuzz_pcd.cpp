// PCD files (parse_pcd): the input is the file, ASCII, binary or binary_compressed. IoError is
// the answer to a malformed header or data that does not match it.

#include "adaptive_lego_loam/io/io_error.h"
#include "adaptive_lego_loam/io/scan_files.h"
#include "fuzz_support.h"

using namespace adaptive_lego_loam;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  try {
    parse_pcd(bytes, "fuzz.pcd");
  } catch (const IoError&) {
  }
  return 0;
}

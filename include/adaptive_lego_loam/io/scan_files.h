#pragma once
// Reading and writing single scans: KITTI .bin (float32 x, y, z, reflectance) and PCD.

#include <string>
#include <vector>

#include "adaptive_lego_loam/core/common/scan.h"
#include "adaptive_lego_loam/io/point_fields.h"

namespace adaptive_lego_loam {

// Throws IoError naming the file when it cannot be opened or its size is not a multiple of 16.
Scan read_kitti_bin(const std::string& path);
// The same from the file's bytes; `source` names them in messages.
Scan parse_kitti_bin(const std::string& bytes, const std::string& source);
void write_kitti_bin(const std::string& path, const Scan& scan);

// PCD v0.5 to v0.7 as PCL writes it (DATA ascii, binary or binary_compressed), with the fields of
// decode_points(). Throws IoError as "<path>:<line>: ..." for a bad header line, and naming the
// file and what was expected when the data does not match the header (POINTS, the fields' SIZE
// and COUNT) or a value does not parse as its TYPE.
Scan read_pcd(const std::string& path, const DecodeOptions& options = {});
// The same from the file's bytes; `source` names them in messages.
Scan parse_pcd(const std::string& bytes, const std::string& source,
               const DecodeOptions& options = {});

// By extension: .bin (KITTI) or .pcd.
Scan read_scan_file(const std::string& path, const DecodeOptions& options = {});

// The .bin and .pcd files directly in `dir`, sorted by name. Throws IoError when `dir` is not a
// readable directory.
std::vector<std::string> list_scan_files(const std::string& dir);

}  // namespace adaptive_lego_loam

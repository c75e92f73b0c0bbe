#include "adaptive_lego_loam/io/scan_files.h"

#include <pcl/PCLPointCloud2.h>
#include <pcl/io/pcd_io.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "adaptive_lego_loam/io/io_error.h"
#include "adaptive_lego_loam/io/point_fields.h"

namespace adaptive_lego_loam {
namespace fs = std::filesystem;

Scan read_kitti_bin(const std::string& path) {
  std::ifstream file(path, std::ios::binary | std::ios::ate);
  if (!file) throw IoError(path + ": cannot open KITTI scan");
  const std::streamsize bytes = file.tellg();
  if (bytes % 16 != 0) {
    throw IoError(path + ": size " + std::to_string(bytes) +
                  " bytes is not a multiple of 16 (float32 x, y, z, reflectance per point)");
  }
  std::vector<float> values(static_cast<std::size_t>(bytes / 4));
  file.seekg(0);
  if (!file.read(reinterpret_cast<char*>(values.data()), bytes)) {
    throw IoError(path + ": read failed");
  }
  Scan scan;
  scan.points.resize(values.size() / 4);
  for (std::size_t i = 0; i < scan.points.size(); ++i) {
    ScanPoint& p = scan.points[i];
    p.x = values[4 * i];
    p.y = values[4 * i + 1];
    p.z = values[4 * i + 2];
    p.intensity = values[4 * i + 3];
  }
  return scan;
}

void write_kitti_bin(const std::string& path, const Scan& scan) {
  std::vector<float> values;
  values.reserve(scan.points.size() * 4);
  for (const ScanPoint& p : scan.points) {
    values.insert(values.end(), {p.x, p.y, p.z, p.intensity});
  }
  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  if (!file) throw IoError(path + ": cannot open for writing");
  file.write(reinterpret_cast<const char*>(values.data()),
             static_cast<std::streamsize>(values.size() * sizeof(float)));
  if (!file) throw IoError(path + ": write failed");
}

Scan read_pcd(const std::string& path) {
  if (!fs::is_regular_file(path)) throw IoError(path + ": no such PCD file");
  pcl::PCLPointCloud2 cloud;
  pcl::PCDReader reader;
  if (reader.read(path, cloud) < 0) throw IoError(path + ": not a readable PCD file");
  return decode_points(packed_points(cloud), path);
}

Scan read_scan_file(const std::string& path) {
  const std::string extension = fs::path(path).extension().string();
  if (extension == ".bin") return read_kitti_bin(path);
  if (extension == ".pcd") return read_pcd(path);
  throw IoError(path + ": unknown scan file type '" + extension + "'; expected .bin or .pcd");
}

std::vector<std::string> list_scan_files(const std::string& dir) {
  std::error_code error;
  if (!fs::is_directory(dir, error)) throw IoError(dir + ": not a directory");
  std::vector<std::string> files;
  for (const auto& entry : fs::directory_iterator(dir, error)) {
    const std::string extension = entry.path().extension().string();
    if (entry.is_regular_file() && (extension == ".bin" || extension == ".pcd")) {
      files.push_back(entry.path().string());
    }
  }
  if (error) throw IoError(dir + ": cannot list: " + error.message());
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace adaptive_lego_loam

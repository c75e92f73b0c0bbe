#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>

#include "adaptive_lego_loam/io/io_error.h"
#include "adaptive_lego_loam/io/point_fields.h"
#include "adaptive_lego_loam/io/scan_files.h"
#include "support/temp_files.h"

using namespace adaptive_lego_loam;
using namespace adaptive_lego_loam::test;
namespace fs = std::filesystem;

namespace {

const std::string kData = TEST_DATA_DIR;

}  // namespace

TEST(ScanFiles, ReadsKittiBin) {
  const std::string path = kData + "/kitti_seq07/velodyne/0000000000.bin";
  const Scan scan = read_kitti_bin(path);
  EXPECT_EQ(scan.points.size(), fs::file_size(path) / 16);
  EXPECT_FALSE(scan.has_ring);
  EXPECT_FALSE(scan.has_time);
}

TEST(ScanFiles, KittiRoundTrip) {
  Scan scan;
  scan.points = {{1.f, 2.f, 3.f, 0.5f}, {-4.f, 5.f, -6.f, 0.25f}};
  const std::string path = temp_path("round_trip.bin");
  write_kitti_bin(path, scan);
  const Scan back = read_kitti_bin(path);
  ASSERT_EQ(back.points.size(), 2u);
  EXPECT_EQ(back.points[1].y, 5.f);
  EXPECT_EQ(back.points[1].intensity, 0.25f);
}

TEST(ScanFiles, TruncatedKittiBinNamesFileAndSize) {
  const std::string path = temp_path("truncated.bin");
  std::ofstream(path, std::ios::binary) << std::string(17, '\0');
  const std::string error = error_of([&] { read_kitti_bin(path); });
  EXPECT_NE(error.find(path), std::string::npos) << error;
  EXPECT_NE(error.find("multiple of 16"), std::string::npos) << error;
  EXPECT_NE(error_of([] { read_kitti_bin("/nonexistent.bin"); }).find("cannot open"),
            std::string::npos);
}

TEST(ScanFiles, ReadsVlp16PcdWithChannelAsRing) {
  const Scan scan = read_pcd(kData + "/vlp16/vlp16_indoor.pcd");
  EXPECT_EQ(scan.points.size(), 14831u);
  EXPECT_TRUE(scan.has_ring);
  EXPECT_TRUE(scan.has_time);
  int max_ring = 0;
  for (const ScanPoint& p : scan.points)
    max_ring = std::max(max_ring, p.ring);
  EXPECT_EQ(max_ring, 15);
}

TEST(ScanFiles, PcdWithoutZIsAClearError) {
  const std::string path = temp_path("no_z.pcd");
  std::ofstream(path) << "VERSION 0.7\nFIELDS x y\nSIZE 4 4\nTYPE F F\nCOUNT 1 1\nWIDTH 1\n"
                         "HEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 1\nDATA ascii\n1 2\n";
  const std::string error = error_of([&] { read_pcd(path); });
  EXPECT_NE(error.find(path), std::string::npos) << error;
  EXPECT_NE(error.find("missing field z"), std::string::npos) << error;
}

TEST(ScanFiles, ListsBinAndPcdSorted) {
  const auto files = list_scan_files(kData + "/kitti_seq07/velodyne");
  ASSERT_EQ(files.size(), 5u);
  EXPECT_TRUE(std::is_sorted(files.begin(), files.end()));
  EXPECT_NE(error_of([] { list_scan_files("/nonexistent_dir"); }).find("not a directory"),
            std::string::npos);
  EXPECT_NE(error_of([] { read_scan_file("scan.ply"); }).find(".bin or .pcd"), std::string::npos);
}

#include <gtest/gtest.h>
#include <pcl/io/pcd_io.h>
#include <pcl/point_types.h>

#include <cmath>
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

TEST(ScanFiles, AnEmptyKittiBinIsAScanWithoutPoints) {
  const std::string path = temp_path("empty.bin");
  std::ofstream(path, std::ios::binary | std::ios::trunc).close();
  EXPECT_TRUE(read_kitti_bin(path).points.empty());
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

namespace {

const char* kXyzHeader =
    "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 2\nHEIGHT 1\n"
    "VIEWPOINT 0 0 0 1 0 0 0\nPOINTS 2\n";

std::string pcd_error(const std::string& bytes) {
  return error_of([&] { parse_pcd(bytes, "scan.pcd"); });
}

}  // namespace

TEST(ScanFiles, ReadsPclWrittenPcdInEveryDataFormat) {
  pcl::PointCloud<pcl::PointXYZI> cloud;
  for (int i = 0; i < 40; ++i) {
    pcl::PointXYZI point;
    point.x = 0.5f * i;
    point.y = -2.25f;
    point.z = i % 3 ? 1.0f : -1.0f;  // repeats: the LZF stream gets back references
    point.intensity = 0.125f * (i % 8);
    cloud.push_back(point);
  }
  pcl::PCDWriter writer;
  const std::string ascii = temp_path("pcl_ascii.pcd"), binary = temp_path("pcl_binary.pcd"),
                    compressed = temp_path("pcl_compressed.pcd");
  ASSERT_EQ(writer.writeASCII(ascii, cloud), 0);
  ASSERT_EQ(writer.writeBinary(binary, cloud), 0);
  ASSERT_EQ(writer.writeBinaryCompressed(compressed, cloud), 0);
  for (const std::string& path : {ascii, binary, compressed}) {
    SCOPED_TRACE(path);
    const Scan scan = read_pcd(path);
    ASSERT_EQ(scan.points.size(), cloud.size());
    for (std::size_t i = 0; i < cloud.size(); ++i) {
      EXPECT_EQ(scan.points[i].x, cloud[i].x);
      EXPECT_EQ(scan.points[i].y, cloud[i].y);
      EXPECT_EQ(scan.points[i].z, cloud[i].z);
      EXPECT_EQ(scan.points[i].intensity, cloud[i].intensity);
    }
  }
}

TEST(ScanFiles, AsciiPcdWithIntegerRingAndNan) {
  const Scan scan = parse_pcd(
      "FIELDS x y z ring time\nSIZE 4 4 4 2 4\nTYPE F F F U F\nWIDTH 2\nDATA ascii\n"
      "1 2 3 7 0.05\n\nnan 5 6 15 0.1\n",
      "scan.pcd");
  ASSERT_EQ(scan.points.size(), 2u);
  EXPECT_TRUE(scan.has_ring && scan.has_time);
  EXPECT_EQ(scan.points[0].ring, 7);
  EXPECT_FLOAT_EQ(scan.points[0].time, 0.05f);
  EXPECT_TRUE(std::isnan(scan.points[1].x));
  EXPECT_EQ(scan.points[1].ring, 15);
}

TEST(ScanFiles, PcdFieldOfAnUnreadableTypeIsPassedOverUnlessItIsACoordinate) {
  // 8-byte integer stamps (as some drivers write them): the scan is read without a time field.
  const Scan scan = parse_pcd(
      "FIELDS x y z timestamp\nSIZE 4 4 4 8\nTYPE F F F U\nWIDTH 1\nDATA ascii\n"
      "1 2 3 1700000000000000000\n",
      "scan.pcd");
  ASSERT_EQ(scan.points.size(), 1u);
  EXPECT_FALSE(scan.has_time);
  EXPECT_FLOAT_EQ(scan.points[0].z, 3.f);
  const std::string error =
      pcd_error("FIELDS x y z\nSIZE 4 4 8\nTYPE F F I\nWIDTH 1\nDATA ascii\n1 2 3\n");
  EXPECT_NE(error.find("scan.pcd: field 'z' has a type that cannot be read"), std::string::npos)
      << error;
}

TEST(ScanFiles, PcdHeaderErrorsNameTheLine) {
  EXPECT_NE(pcd_error("VERSION 0.7\nFIELDS x y z\nSIZE 4 3 4\n")
                .find("scan.pcd:3: SIZE 3: "
                      "expected 1, 2, 4 or 8"),
            std::string::npos);
  EXPECT_NE(pcd_error("# comment\nHEIGHT\n").find("scan.pcd:2: HEIGHT: expected one number"),
            std::string::npos);
  EXPECT_NE(pcd_error(std::string(kXyzHeader) + "DATA\n").find("scan.pcd:10: DATA: expected one"),
            std::string::npos);
  EXPECT_NE(pcd_error("FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 1\n").find("no DATA line"),
            std::string::npos);
  EXPECT_NE(pcd_error("FIELDS x y z\nSIZE 4 4\nTYPE F F F\nWIDTH 1\nDATA ascii\n")
                .find("scan.pcd: PCD header has 2 SIZE entries for 3 FIELDS"),
            std::string::npos);
}

TEST(ScanFiles, PcdPointsMustMatchWidthTimesHeightAndTheData) {
  std::string header = kXyzHeader;
  EXPECT_NE(pcd_error(header + "DATA ascii\n1 2 3\n").find("PCD data holds 1 points, expected 2"),
            std::string::npos);
  EXPECT_NE(pcd_error(header + "DATA ascii\n1 2 3\n4 5\n").find("scan.pcd:12: expected 3 values"),
            std::string::npos);
  header.replace(header.find("POINTS 2"), 8, "POINTS 3");
  EXPECT_NE(pcd_error(header + "DATA ascii\n").find("POINTS 3 but WIDTH x HEIGHT = 2"),
            std::string::npos);
}

TEST(ScanFiles, PcdHeaderCannotClaimMoreThanTheFileHolds) {
  // A header alone must not make the reader allocate: 4e9 points of 12 bytes in a 24-byte body.
  const std::string binary =
      "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 4000000000\nDATA binary\n" +
      std::string(24, '\0');
  EXPECT_NE(pcd_error(binary).find(
                "PCD binary data holds 24 bytes, expected 4000000000 points x 12 bytes"),
            std::string::npos);
  const std::string compressed_header =
      "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 100000000\nDATA binary_compressed\n";
  const uint32_t sizes[2] = {4, 1200000000};  // 4 LZF bytes for 1.2 GB of records
  std::string body(reinterpret_cast<const char*>(sizes), sizeof(sizes));
  EXPECT_NE(pcd_error(compressed_header + body + "abcd").find("compressed size 4 is too small"),
            std::string::npos);
  EXPECT_NE(pcd_error(compressed_header + body).find("compressed size 4 runs past the end"),
            std::string::npos);
}

TEST(ScanFiles, CorruptLzfDataIsAnError) {
  const std::string header =
      "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 1\nDATA binary_compressed\n";
  // A back reference (control 0x20) before any output: nothing to refer to.
  const uint32_t sizes[2] = {2, 12};
  const std::string body =
      std::string(reinterpret_cast<const char*>(sizes), sizeof(sizes)) + std::string("\x20\x00", 2);
  EXPECT_NE(pcd_error(header + body).find("not a valid LZF stream of 12 bytes"), std::string::npos);
}

TEST(ScanFiles, ParsesKittiBinFromMemory) {
  const float values[8] = {1, 2, 3, 0.5f, -4, 5, -6, 0.25f};
  const Scan scan = parse_kitti_bin(std::string(reinterpret_cast<const char*>(values), 32), "m");
  ASSERT_EQ(scan.points.size(), 2u);
  EXPECT_EQ(scan.points[1].z, -6.f);
  EXPECT_NE(error_of([] {
              parse_kitti_bin(std::string(20, '\0'), "scan 7");
            }).find("scan 7: size 20 bytes is not a multiple of 16"),
            std::string::npos);
}

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

TEST(PointFields, DecodesIntegerRingAndNanosecondTime) {
  struct Record {
    float x, y, z;
    uint16_t ring;
    uint32_t t;
  } __attribute__((packed));
  Record records[2] = {{1, 2, 3, 7, 50000000}, {4, 5, 6, 9, 0}};
  PackedPoints packed;
  packed.fields = {
      {"x", 0, 7, 1}, {"y", 4, 7, 1}, {"z", 8, 7, 1}, {"ring", 12, 4, 1}, {"t", 14, 6, 1}};
  packed.data = reinterpret_cast<const uint8_t*>(records);
  packed.data_size = sizeof(records);
  packed.points = 2;
  packed.point_step = sizeof(Record);
  const Scan scan = decode_points(packed, "test");
  ASSERT_EQ(scan.points.size(), 2u);
  EXPECT_TRUE(scan.has_ring && scan.has_time);
  EXPECT_EQ(scan.points[0].ring, 7);
  EXPECT_FLOAT_EQ(scan.points[0].time, 0.05f);
  EXPECT_EQ(scan.points[1].z, 6.f);
}

TEST(PointFields, ShortDataAndFieldPastStepAreErrors) {
  float values[3] = {1, 2, 3};
  PackedPoints packed;
  packed.fields = {{"x", 0, 7, 1}, {"y", 4, 7, 1}, {"z", 8, 7, 1}};
  packed.data = reinterpret_cast<const uint8_t*>(values);
  packed.data_size = sizeof(values);
  packed.points = 2;
  packed.point_step = 12;
  EXPECT_NE(error_of([&] { decode_points(packed, "/velodyne_points"); }).find("expected 2 points"),
            std::string::npos);
  packed.points = 1;
  packed.fields[2].offset = 10;
  EXPECT_NE(error_of([&] { decode_points(packed, "/velodyne_points"); }).find("runs past"),
            std::string::npos);
}

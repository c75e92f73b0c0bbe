#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <tuple>
#include <vector>

#include "adaptive_lego_loam/io/io_error.h"
#include "adaptive_lego_loam/io/point_fields.h"
#include "adaptive_lego_loam/io/scan_files.h"
#include "support/temp_files.h"

using namespace adaptive_lego_loam;
using namespace adaptive_lego_loam::test;
namespace fs = std::filesystem;

namespace {

// `records` (a packed struct per point) as one row of points described by `fields`.
template <typename Record, std::size_t N>
PackedPoints packed_rows(const Record (&records)[N], std::vector<FieldDescription> fields) {
  PackedPoints packed;
  packed.fields = std::move(fields);
  packed.data = reinterpret_cast<const uint8_t*>(records);
  packed.data_size = sizeof(records);
  packed.width = N;
  packed.point_step = sizeof(Record);
  return packed;
}

}  // namespace

TEST(PointFields, DecodesIntegerRingAndNanosecondTime) {
  struct Record {
    float x, y, z;
    uint16_t ring;
    uint32_t t;
  } __attribute__((packed));
  Record records[2] = {{1, 2, 3, 7, 50000000}, {4, 5, 6, 9, 0}};
  const PackedPoints packed = packed_rows(
      records,
      {{"x", 0, 7, 1}, {"y", 4, 7, 1}, {"z", 8, 7, 1}, {"ring", 12, 4, 1}, {"t", 14, 6, 1}});
  const Scan scan = decode_points(packed, "test");
  ASSERT_EQ(scan.points.size(), 2u);
  EXPECT_TRUE(scan.has_ring && scan.has_time);
  EXPECT_EQ(scan.points[0].ring, 7);
  EXPECT_FLOAT_EQ(scan.points[0].time, 0.05f);
  EXPECT_EQ(scan.points[1].z, 6.f);
}

// A driver's usual layout (float32 x y z intensity time, uint16 ring, read without a type switch)
// and the same points in doubles (read value by value) give the same scan.
TEST(PointFields, TheUsualLayoutAndDoublesDecodeAlike) {
  struct Usual {
    float x, y, z, intensity;
    uint16_t ring;
    float time;
  } __attribute__((packed));
  struct Doubles {
    double x, y, z, intensity;
    uint16_t ring;
    double time;
  } __attribute__((packed));
  const Usual usual[2] = {{1.5f, -2.25f, 3, 40, 15, 0.025f}, {-4, 5.125f, -6.5f, 0, 0, 0.099f}};
  Doubles doubles[2];
  for (int i = 0; i < 2; ++i) {
    doubles[i] = {usual[i].x,         usual[i].y,    usual[i].z,
                  usual[i].intensity, usual[i].ring, usual[i].time};
  }
  const Scan fast = decode_points(packed_rows(usual, {{"x", 0, 7, 1},
                                                      {"y", 4, 7, 1},
                                                      {"z", 8, 7, 1},
                                                      {"intensity", 12, 7, 1},
                                                      {"ring", 16, 4, 1},
                                                      {"time", 18, 7, 1}}),
                                  "usual");
  const Scan slow = decode_points(packed_rows(doubles, {{"x", 0, 8, 1},
                                                        {"y", 8, 8, 1},
                                                        {"z", 16, 8, 1},
                                                        {"intensity", 24, 8, 1},
                                                        {"ring", 32, 4, 1},
                                                        {"time", 34, 8, 1}}),
                                  "doubles");
  ASSERT_EQ(fast.points.size(), 2u);
  ASSERT_EQ(slow.points.size(), 2u);
  EXPECT_TRUE(fast.has_ring && fast.has_time);
  for (int i = 0; i < 2; ++i) {
    const ScanPoint &a = fast.points[i], &b = slow.points[i];
    // Copies: a packed member cannot be bound to the reference EXPECT_EQ takes.
    const float x = usual[i].x, z = usual[i].z, time = usual[i].time;
    const int ring = usual[i].ring;
    EXPECT_EQ(a.x, x);
    EXPECT_EQ(a.z, z);
    EXPECT_EQ(a.ring, ring);
    EXPECT_EQ(a.time, time);
    EXPECT_EQ(std::tie(a.x, a.y, a.z, a.intensity, a.ring, a.time),
              std::tie(b.x, b.y, b.z, b.intensity, b.ring, b.time));
  }
}

// Coordinates as 16-bit integers (as some drivers pack them) are read as the numbers they hold.
TEST(PointFields, Int16CoordinatesAreReadAsNumbers) {
  struct Record {
    int16_t x, y, z;
  } __attribute__((packed));
  const Record records[2] = {{1, -2, 3}, {-300, 400, -5}};
  const PackedPoints packed =
      packed_rows(records, {{"x", 0, 3, 1}, {"y", 2, 3, 1}, {"z", 4, 3, 1}});
  const Scan scan = decode_points(packed, "test");
  ASSERT_EQ(scan.points.size(), 2u);
  EXPECT_EQ(scan.points[0].y, -2.f);
  EXPECT_EQ(scan.points[1].x, -300.f);
  EXPECT_FALSE(scan.has_ring || scan.has_time);
}

// A node decodes every message into the same Scan: nothing of a richer, longer scan before stays.
TEST(PointFields, DecodingIntoAScanLeavesNothingOfTheScanBefore) {
  struct Full {
    float x, y, z, intensity;
    uint16_t ring;
  } __attribute__((packed));
  const Full full[3] = {{1, 2, 3, 40, 5}, {4, 5, 6, 50, 6}, {7, 8, 9, 60, 7}};
  struct Bare {
    float x, y, z;
  };
  const Bare bare[2] = {{-1, -2, -3}, {-4, -5, -6}};
  Scan scan = decode_points(packed_rows(full, {{"x", 0, 7, 1},
                                               {"y", 4, 7, 1},
                                               {"z", 8, 7, 1},
                                               {"intensity", 12, 7, 1},
                                               {"ring", 16, 4, 1}}),
                            "first");
  ASSERT_TRUE(scan.has_ring);
  decode_points(packed_rows(bare, {{"x", 0, 7, 1}, {"y", 4, 7, 1}, {"z", 8, 7, 1}}), "second",
                scan);
  ASSERT_EQ(scan.points.size(), 2u);
  EXPECT_FALSE(scan.has_ring || scan.has_time);
  for (const ScanPoint& p : scan.points) {
    EXPECT_EQ(p.intensity, 0.f);
    EXPECT_EQ(p.ring, -1);
  }
  EXPECT_EQ(scan.points[1].x, -4.f);
  EXPECT_EQ(scan.points[1].z, -6.f);
}

// A big-endian cloud (is_bigendian): every multi-byte field is byte-swapped, single bytes not.
TEST(PointFields, BigEndianRecordsAreSwapped) {
  struct Record {
    uint8_t x[4], y[4], z[4];
    uint8_t ring[2];
    uint8_t channel_byte;
  } __attribute__((packed));
  const auto big = [](float value, uint8_t(&out)[4]) {
    uint8_t bytes[4];
    std::memcpy(bytes, &value, 4);
    for (int i = 0; i < 4; ++i)
      out[i] = bytes[3 - i];
  };
  Record records[1] = {};
  big(1.5f, records[0].x);
  big(-2.f, records[0].y);
  big(300.f, records[0].z);
  records[0].ring[0] = 0x01;  // 0x0102 = 258
  records[0].ring[1] = 0x02;
  records[0].channel_byte = 9;
  PackedPoints packed = packed_rows(records, {{"x", 0, 7, 1},
                                              {"y", 4, 7, 1},
                                              {"z", 8, 7, 1},
                                              {"ring", 12, 4, 1},
                                              {"intensity", 14, 2, 1}});
  packed.big_endian = true;
  const Scan scan = decode_points(packed, "test");
  ASSERT_EQ(scan.points.size(), 1u);
  EXPECT_EQ(scan.points[0].x, 1.5f);
  EXPECT_EQ(scan.points[0].y, -2.f);
  EXPECT_EQ(scan.points[0].z, 300.f);
  EXPECT_EQ(scan.points[0].ring, 258);
  EXPECT_EQ(scan.points[0].intensity, 9.f);
}

TEST(PointFields, ShortDataAndFieldPastStepAreErrors) {
  float values[3] = {1, 2, 3};
  PackedPoints packed;
  packed.fields = {{"x", 0, 7, 1}, {"y", 4, 7, 1}, {"z", 8, 7, 1}};
  packed.data = reinterpret_cast<const uint8_t*>(values);
  packed.data_size = sizeof(values);
  packed.width = 2;
  packed.point_step = 12;
  EXPECT_NE(error_of([&] { decode_points(packed, "/velodyne_points"); }).find("expected 2 points"),
            std::string::npos);
  packed.width = 1;
  packed.fields[2].offset = 10;
  EXPECT_NE(error_of([&] { decode_points(packed, "/velodyne_points"); }).find("runs past"),
            std::string::npos);
}

namespace {

// x, y, z float32 records of `width` x `height` points, `padding` bytes after each row.
struct Rows {
  std::vector<uint8_t> bytes;
  PackedPoints packed;
};

Rows xyz_rows(uint32_t width, uint32_t height, uint32_t padding) {
  Rows rows;
  for (uint32_t row = 0; row < height; ++row) {
    for (uint32_t col = 0; col < width; ++col) {
      const float xyz[3] = {float(row), float(col), float(10 * row + col)};
      const auto* bytes = reinterpret_cast<const uint8_t*>(xyz);
      rows.bytes.insert(rows.bytes.end(), bytes, bytes + sizeof(xyz));
    }
    rows.bytes.resize(rows.bytes.size() + padding, 0xee);
  }
  rows.packed.fields = {{"x", 0, 7, 1}, {"y", 4, 7, 1}, {"z", 8, 7, 1}};
  rows.packed.data = rows.bytes.data();
  rows.packed.data_size = rows.bytes.size();
  rows.packed.width = width;
  rows.packed.height = height;
  rows.packed.point_step = 12;
  rows.packed.row_step = width * 12 + padding;
  return rows;
}

}  // namespace

TEST(PointFields, OrganizedRowsSkipTheirPadding) {
  const Rows rows = xyz_rows(2, 3, 8);
  const Scan scan = decode_points(rows.packed, "/os_cloud");
  ASSERT_EQ(scan.points.size(), 6u);
  EXPECT_EQ(scan.points[3].x, 1.f);  // row 1, column 1
  EXPECT_EQ(scan.points[3].y, 1.f);
  EXPECT_EQ(scan.points[5].z, 21.f);
}

TEST(PointFields, RowStepShorterThanARowIsAnError) {
  Rows rows = xyz_rows(2, 2, 0);
  rows.packed.row_step = 20;
  const std::string error = error_of([&] { decode_points(rows.packed, "/os_cloud"); });
  EXPECT_NE(error.find("/os_cloud: row_step 20 is less than width 2 x point_step 12"),
            std::string::npos)
      << error;
}

TEST(PointFields, WidthTimesHeightBeyondTheDataIsAnErrorNotAnAllocation) {
  // 2^30 x 2^30 points of 16 bytes is 2^64 bytes: the product wraps to 0 in 64 bits.
  Rows rows = xyz_rows(1, 1, 4);
  rows.packed.width = 1u << 30;
  rows.packed.height = 1u << 30;
  rows.packed.point_step = 16;
  rows.packed.row_step = 0;
  const std::string error = error_of([&] { decode_points(rows.packed, "/velodyne_points"); });
  EXPECT_NE(
      error.find("/velodyne_points: data holds 16 bytes, expected 1152921504606846976 points"),
      std::string::npos)
      << error;
}

TEST(PointFields, RingBeyondInt32ReadsAsNoLaser) {
  struct Record {
    float x, y, z;
    uint32_t ring;
  };
  const Record records[2] = {{1, 2, 3, 4294967295u}, {4, 5, 6, 12}};
  const PackedPoints packed =
      packed_rows(records, {{"x", 0, 7, 1}, {"y", 4, 7, 1}, {"z", 8, 7, 1}, {"ring", 12, 6, 1}});
  const Scan scan = decode_points(packed, "/points");
  ASSERT_EQ(scan.points.size(), 2u);
  EXPECT_EQ(scan.points[0].ring, -1);
  EXPECT_EQ(scan.points[1].ring, 12);
}

// Hesai's and RoboSense's absolute float64 stamps become offsets from the sweep's earliest point,
// to the microsecond; relative float64 times stay as they are.
TEST(PointFields, ClockStampsBecomeOffsetsFromTheEarliest) {
  struct Record {
    float x, y, z;
    double timestamp;
  } __attribute__((packed));
  const Record clock[3] = {
      {1, 0, 0, 1712345678.100250}, {2, 0, 0, 1712345678.000125}, {3, 0, 0, 1712345678.050000}};
  const std::vector<FieldDescription> fields = {
      {"x", 0, 7, 1}, {"y", 4, 7, 1}, {"z", 8, 7, 1}, {"timestamp", 12, 8, 1}};
  const Scan scan = decode_points(packed_rows(clock, fields), "clock");
  ASSERT_TRUE(scan.has_time);
  EXPECT_NEAR(scan.points[0].time, 0.100125, 1e-7);
  EXPECT_EQ(scan.points[1].time, 0.f);
  EXPECT_NEAR(scan.points[2].time, 0.049875, 1e-7);
  const Record offsets[2] = {{1, 0, 0, 0.075}, {2, 0, 0, 0.025}};
  const Scan relative = decode_points(packed_rows(offsets, fields), "offsets");
  EXPECT_EQ(relative.points[0].time, 0.075f);
  EXPECT_EQ(relative.points[1].time, 0.025f);
}

// The legacy OS1 driver's float32 t is the column's share of the sweep: seconds with the sweep's
// period, left out without it.
TEST(PointFields, AFloatTIsAShareOfTheSweep) {
  struct Record {
    float x, y, z, t;
  };
  const Record records[2] = {{1, 2, 3, 0.5f}, {4, 5, 6, 0.25f}};
  const std::vector<FieldDescription> fields = {
      {"x", 0, 7, 1}, {"y", 4, 7, 1}, {"z", 8, 7, 1}, {"t", 12, 7, 1}};
  const Scan at_20_hz = decode_points(packed_rows(records, fields), "os1", {0.05});
  ASSERT_TRUE(at_20_hz.has_time);
  EXPECT_FLOAT_EQ(at_20_hz.points[0].time, 0.025f);
  EXPECT_FLOAT_EQ(at_20_hz.points[1].time, 0.0125f);
  EXPECT_FALSE(decode_points(packed_rows(records, fields), "os1").has_time);
}

#pragma once
// Decoding of packed point records (PCD files, sensor_msgs/PointCloud2) into a Scan, in one
// place so that every reader accepts the same field names and types.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "adaptive_lego_loam/core/common/scan.h"

namespace adaptive_lego_loam {

// Same numbering as sensor_msgs/PointField and pcl::PCLPointField.
enum class FieldType : uint8_t {
  kInt8 = 1,
  kUint8 = 2,
  kInt16 = 3,
  kUint16 = 4,
  kInt32 = 5,
  kUint32 = 6,
  kFloat32 = 7,
  kFloat64 = 8
};

struct FieldDescription {
  std::string name;
  uint32_t offset = 0;
  uint8_t datatype = 0;
  uint32_t count = 1;
};

struct PackedPoints {
  std::vector<FieldDescription> fields;
  const uint8_t* data = nullptr;
  std::size_t data_size = 0;  // bytes available at `data`
  uint32_t width = 0;         // points per row
  uint32_t height = 1;        // rows
  uint32_t point_step = 0;
  uint32_t row_step = 0;  // bytes from one row to the next; 0: width * point_step
  bool big_endian = false;
};

// The packed records of a pcl::PCLPointCloud2 or a sensor_msgs::PointCloud2 (the same fields
// under the same names), viewed without a copy: `cloud` must outlive the result.
template <class PointCloud2>
PackedPoints packed_points(const PointCloud2& cloud) {
  PackedPoints packed;
  for (const auto& field : cloud.fields) {
    packed.fields.push_back({field.name, field.offset, field.datatype, field.count});
  }
  packed.data = cloud.data.data();
  packed.data_size = cloud.data.size();
  packed.width = cloud.width;
  packed.height = cloud.height;
  packed.point_step = cloud.point_step;
  packed.row_step = cloud.row_step;
  packed.big_endian = cloud.is_bigendian;
  return packed;
}

// What the records alone do not say.
struct DecodeOptions {
  // s: the sweep's period, which turns a time field given as a fraction of the sweep (the legacy
  // OS1 driver's float t) into seconds; 0: unknown, and such a time field is left out.
  double sweep_period = 0.0;
};

// The name of a PointField datatype ("float32", "uint16", ...), or "datatype N" for another N.
std::string field_type_name(uint8_t datatype);

// Accepted names: x, y, z (required); intensity | reflectance | i; ring | channel (any integer
// type); time | t | time_stamp | timestamp. A time field becomes seconds since the sweep's start:
// integer types are nanoseconds (Ouster's t, nebula's time_stamp), a float32 t is a fraction of
// the sweep (the legacy OS1 driver's; see DecodeOptions), other floats are seconds; float64 stamps
// of a clock (Hesai's and RoboSense's absolute timestamp, 1e6 s and more) become offsets from the
// earliest. Throws IoError naming `source` when a required field is missing, has a non-numeric
// type or lies outside the record, when a ring field is not of an integer type (naming the type
// found and the types expected), when a row is longer than the row step, or when the data is
// short. An optional field of a type that cannot be read (8-byte integers in a PCD) is passed
// over. A ring value beyond int32 reads as -1 (no laser).
Scan decode_points(const PackedPoints& packed, const std::string& source,
                   const DecodeOptions& options = {});
// The same into `scan`, whose point buffer is reused (its stamp is left as it was).
void decode_points(const PackedPoints& packed, const std::string& source, Scan& scan,
                   const DecodeOptions& options = {});

}  // namespace adaptive_lego_loam

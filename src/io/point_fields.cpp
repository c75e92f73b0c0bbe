#include "adaptive_lego_loam/io/point_fields.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "adaptive_lego_loam/io/io_error.h"

namespace adaptive_lego_loam {
namespace {

std::size_t type_size(uint8_t datatype) {
  switch (static_cast<FieldType>(datatype)) {
    case FieldType::kInt8:
    case FieldType::kUint8:
      return 1;
    case FieldType::kInt16:
    case FieldType::kUint16:
      return 2;
    case FieldType::kInt32:
    case FieldType::kUint32:
    case FieldType::kFloat32:
      return 4;
    case FieldType::kFloat64:
      return 8;
  }
  return 0;
}

bool is_integer(uint8_t datatype) {
  return datatype >= static_cast<uint8_t>(FieldType::kInt8) &&
         datatype <= static_cast<uint8_t>(FieldType::kUint32);
}

template <typename T>
T load(const uint8_t* at, bool swap) {
  uint8_t bytes[sizeof(T)];
  std::memcpy(bytes, at, sizeof(T));
  if (swap) std::reverse(bytes, bytes + sizeof(T));
  T value;
  std::memcpy(&value, bytes, sizeof(T));
  return value;
}

inline double read_value(const uint8_t* at, uint8_t datatype, bool swap) {
  switch (static_cast<FieldType>(datatype)) {
    case FieldType::kInt8:
      return load<int8_t>(at, false);
    case FieldType::kUint8:
      return load<uint8_t>(at, false);
    case FieldType::kInt16:
      return load<int16_t>(at, swap);
    case FieldType::kUint16:
      return load<uint16_t>(at, swap);
    case FieldType::kInt32:
      return load<int32_t>(at, swap);
    case FieldType::kUint32:
      return load<uint32_t>(at, swap);
    case FieldType::kFloat32:
      return load<float>(at, swap);
    case FieldType::kFloat64:
      return load<double>(at, swap);
  }
  return std::numeric_limits<double>::quiet_NaN();
}

// Finds the first field whose name is one of `names`; checks its type and extent. An optional
// field (intensity, ring, time) of a type that cannot be read is passed over; a coordinate's is
// an error.
const FieldDescription* find_field(const PackedPoints& packed,
                                   std::initializer_list<const char*> names,
                                   const std::string& source, bool required = false) {
  for (const char* name : names) {
    for (const FieldDescription& field : packed.fields) {
      if (field.name != name) continue;
      const std::size_t size = type_size(field.datatype);
      if (size == 0) {
        if (!required) continue;
        throw IoError(source + ": field '" + field.name + "' has a type that cannot be read " +
                      "(datatype " + std::to_string(field.datatype) +
                      "); expected PointField types 1..8 (PCD: F 4 or 8, I or U 1, 2 or 4)");
      }
      if (field.offset + size > packed.point_step) {
        throw IoError(source + ": field '" + field.name + "' at offset " +
                      std::to_string(field.offset) + " runs past the point step of " +
                      std::to_string(packed.point_step) + " bytes");
      }
      return &field;
    }
  }
  return nullptr;
}

// A ring value that does not fit the core's int32 is no laser index.
int32_t ring_value(double value) {
  const bool fits =
      value >= std::numeric_limits<int32_t>::min() && value <= std::numeric_limits<int32_t>::max();
  return fits ? static_cast<int32_t>(value) : -1;
}

[[noreturn]] void fail_missing_coordinate(const PackedPoints& packed, const char* name,
                                          const std::string& source) {
  std::string names;
  for (const auto& field : packed.fields)
    names += (names.empty() ? "" : " ") + field.name;
  throw IoError(source + ": missing field " + name +
                "; fields present: " + (names.empty() ? "none" : names));
}

// The bytes from one row to the next; checks that the rows fit the data.
std::size_t checked_row_step(const PackedPoints& packed, const std::string& source) {
  const std::size_t row_bytes = std::size_t{packed.width} * packed.point_step;
  const std::size_t row_step = packed.row_step ? packed.row_step : row_bytes;
  if (row_step < row_bytes) {
    throw IoError(source + ": row_step " + std::to_string(row_step) + " is less than width " +
                  std::to_string(packed.width) + " x point_step " +
                  std::to_string(packed.point_step) + " bytes");
  }
  std::size_t rows_before_last = 0;
  const bool fits =
      row_bytes <= packed.data_size &&
      !__builtin_mul_overflow(std::size_t{packed.height - 1}, row_step, &rows_before_last) &&
      rows_before_last <= packed.data_size - row_bytes;
  if (!fits) {
    const std::string layout =
        row_step == row_bytes
            ? std::to_string(std::size_t{packed.width} * packed.height) + " points x " +
                  std::to_string(packed.point_step)
            : std::to_string(packed.height) + " rows x row_step " + std::to_string(row_step);
    throw IoError(source + ": data holds " + std::to_string(packed.data_size) +
                  " bytes, expected " + layout + " bytes");
  }
  return row_step;
}

// The fields a point is read from: coordinates, then the optional ones (null when absent).
struct PointFieldSet {
  const FieldDescription *x, *y, *z, *intensity, *ring, *time;
};

bool has_type(const FieldDescription* field, FieldType type) {
  return !field || field->datatype == static_cast<uint8_t>(type);
}

// What nearly every driver sends: little-endian float32 coordinates, intensity and time in
// seconds, a uint16 ring. Read without a switch on the type of every value, which costs more
// than the rest of the decoding.
bool native_layout(const PackedPoints& packed, const PointFieldSet& f) {
  return !packed.big_endian && has_type(f.x, FieldType::kFloat32) &&
         has_type(f.y, FieldType::kFloat32) && has_type(f.z, FieldType::kFloat32) &&
         has_type(f.intensity, FieldType::kFloat32) && has_type(f.ring, FieldType::kUint16) &&
         has_type(f.time, FieldType::kFloat32);
}

// Calls read_point(record, point) for every record of `packed`, in order, into scan.points.
template <typename ReadPoint>
void for_each_record(const PackedPoints& packed, std::size_t row_step, Scan& scan,
                     ReadPoint read_point) {
  ScanPoint* p = scan.points.data();
  for (uint32_t row = 0; row < packed.height; ++row) {
    const uint8_t* record = packed.data + row * row_step;
    for (uint32_t column = 0; column < packed.width; ++column, ++p, record += packed.point_step)
      read_point(record, *p);
  }
}

// A time field and how its values become seconds since the sweep's start: (value - origin) *
// scale.
struct TimeField {
  const FieldDescription* field = nullptr;
  double scale = 1.0;
  double origin = 0.0;
};

// Seconds from which a stamp is a clock's, not an offset within the sweep (about 12 days).
constexpr double kClockSeconds = 1e6;

// The smallest value of the field at or beyond `threshold` (NaN when there is none).
double earliest_at_least(const PackedPoints& packed, std::size_t row_step,
                         const FieldDescription& field, double threshold) {
  double earliest = std::numeric_limits<double>::quiet_NaN();
  for (uint32_t row = 0; row < packed.height; ++row) {
    const uint8_t* record = packed.data + row * row_step + field.offset;
    for (uint32_t column = 0; column < packed.width; ++column, record += packed.point_step) {
      const double value = read_value(record, field.datatype, packed.big_endian);
      if (value >= threshold && !(value >= earliest)) earliest = value;
    }
  }
  return earliest;
}

TimeField time_field(const PackedPoints& packed, std::size_t row_step,
                     const FieldDescription* field, const DecodeOptions& options) {
  if (!field) return {};
  TimeField time{field};
  if (is_integer(field->datatype)) {
    time.scale = 1e-9;  // nanoseconds (Ouster's t, nebula's time_stamp)
  } else if (field->name == "t" && field->datatype == static_cast<uint8_t>(FieldType::kFloat32)) {
    // The legacy OS1 driver's t: the column's share of the sweep, in [0, 1).
    if (!(options.sweep_period > 0.0)) return {};
    time.scale = options.sweep_period;
  }
  // A float64 stamp of a clock (Hesai's and RoboSense's absolute timestamp) loses its
  // sub-millisecond part as a float: offsets from the earliest stamp keep it.
  const bool can_hold_a_clock = field->datatype == static_cast<uint8_t>(FieldType::kFloat64);
  if (can_hold_a_clock && packed.width > 0 && packed.height > 0) {
    const double earliest = earliest_at_least(packed, row_step, *field, kClockSeconds / time.scale);
    if (std::isfinite(earliest)) time.origin = earliest;
  }
  return time;
}

void decode_native(const PackedPoints& packed, std::size_t row_step, const PointFieldSet& f,
                   Scan& scan) {
  for_each_record(packed, row_step, scan, [&f](const uint8_t* record, ScanPoint& p) {
    p.x = load<float>(record + f.x->offset, false);
    p.y = load<float>(record + f.y->offset, false);
    p.z = load<float>(record + f.z->offset, false);
    p.intensity = f.intensity ? load<float>(record + f.intensity->offset, false) : 0.f;
    p.ring = f.ring ? load<uint16_t>(record + f.ring->offset, false) : -1;
    p.time = f.time ? load<float>(record + f.time->offset, false) : 0.f;
  });
}

void decode_any(const PackedPoints& packed, std::size_t row_step, const PointFieldSet& f,
                const TimeField& time, Scan& scan) {
  const bool swap = packed.big_endian;
  const auto read = [swap](const uint8_t* record, const FieldDescription* field) {
    return read_value(record + field->offset, field->datatype, swap);
  };
  for_each_record(packed, row_step, scan, [&](const uint8_t* record, ScanPoint& p) {
    p.x = static_cast<float>(read(record, f.x));
    p.y = static_cast<float>(read(record, f.y));
    p.z = static_cast<float>(read(record, f.z));
    p.intensity = f.intensity ? static_cast<float>(read(record, f.intensity)) : 0.f;
    p.ring = f.ring ? ring_value(read(record, f.ring)) : -1;
    p.time = f.time ? static_cast<float>((read(record, f.time) - time.origin) * time.scale) : 0.f;
  });
}

}  // namespace

std::string field_type_name(uint8_t datatype) {
  static const char* const kNames[] = {"int8",  "uint8",  "int16",   "uint16",
                                       "int32", "uint32", "float32", "float64"};
  if (datatype >= 1 && datatype <= 8) return kNames[datatype - 1];
  return "datatype " + std::to_string(datatype);
}

void decode_points(const PackedPoints& packed, const std::string& source, Scan& scan,
                   const DecodeOptions& options) {
  const FieldDescription* x = find_field(packed, {"x"}, source, true);
  const FieldDescription* y = find_field(packed, {"y"}, source, true);
  const FieldDescription* z = find_field(packed, {"z"}, source, true);
  if (!x) fail_missing_coordinate(packed, "x", source);
  if (!y) fail_missing_coordinate(packed, "y", source);
  if (!z) fail_missing_coordinate(packed, "z", source);
  const bool empty = packed.width == 0 || packed.height == 0;
  const std::size_t row_step = empty ? 0 : checked_row_step(packed, source);
  const FieldDescription* intensity = find_field(packed, {"intensity", "reflectance", "i"}, source);
  const FieldDescription* ring = find_field(packed, {"ring", "channel"}, source);
  const FieldDescription* time_candidate =
      find_field(packed, {"time", "t", "time_stamp", "timestamp"}, source);
  if (ring && !is_integer(ring->datatype)) {
    throw IoError(source + ": field '" + ring->name + "' has type " +
                  field_type_name(ring->datatype) +
                  "; expected an integer type (uint8, uint16, uint32, int8, int16 or int32)");
  }
  const TimeField time = time_field(packed, row_step, time_candidate, options);

  scan.has_ring = ring != nullptr;
  scan.has_time = time.field != nullptr;
  // Every field of every point is written below: the buffer of a scan before leaves nothing.
  scan.points.resize(empty ? 0 : std::size_t{packed.width} * packed.height);
  if (empty) return;
  const PointFieldSet fields{x, y, z, intensity, ring, time.field};
  if (native_layout(packed, fields) && time.scale == 1.0 && time.origin == 0.0) {
    decode_native(packed, row_step, fields, scan);
  } else {
    decode_any(packed, row_step, fields, time, scan);
  }
}

Scan decode_points(const PackedPoints& packed, const std::string& source,
                   const DecodeOptions& options) {
  Scan scan;
  decode_points(packed, source, scan, options);
  return scan;
}

}  // namespace adaptive_lego_loam

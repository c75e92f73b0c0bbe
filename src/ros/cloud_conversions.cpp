#include "adaptive_lego_loam/ros/cloud_conversions.h"

#include <cstring>

namespace adaptive_lego_loam::ros_bridge {

Scan from_ros(const sensor_msgs::PointCloud2& msg, const std::string& source,
              const DecodeOptions& options) {
  Scan scan;
  from_ros(msg, source, scan, options);
  return scan;
}

void from_ros(const sensor_msgs::PointCloud2& msg, const std::string& source, Scan& scan,
              const DecodeOptions& options) {
  decode_points(packed_points(msg), source, scan, options);
  scan.stamp = msg.header.stamp.toSec();
}

namespace {

sensor_msgs::PointField field(const std::string& name, uint32_t offset, uint8_t datatype) {
  sensor_msgs::PointField f;
  f.name = name;
  f.offset = offset;
  f.datatype = datatype;
  f.count = 1;
  return f;
}

// x y z intensity [time ring], every field at an offset that is a multiple of its size and the
// point step a multiple of 4, so that readers may take the fields in place. `rings`, when given,
// replaces each point's ring.
sensor_msgs::PointCloud2 encode(const std::vector<ScanPoint>& points,
                                const std::vector<uint16_t>* rings, const std_msgs::Header& header,
                                bool with_ring_and_time) {
  using sensor_msgs::PointField;
  sensor_msgs::PointCloud2 msg;
  msg.header = header;
  msg.fields = {field("x", 0, PointField::FLOAT32), field("y", 4, PointField::FLOAT32),
                field("z", 8, PointField::FLOAT32), field("intensity", 12, PointField::FLOAT32)};
  msg.point_step = 16;
  if (with_ring_and_time) {
    msg.fields.push_back(field("time", 16, PointField::FLOAT32));
    msg.fields.push_back(field("ring", 20, PointField::UINT16));
    msg.point_step = 24;  // 2 bytes of padding
  }
  msg.height = 1;
  msg.width = static_cast<uint32_t>(points.size());
  msg.row_step = msg.point_step * msg.width;
  msg.is_bigendian = false;
  msg.is_dense = false;
  msg.data.assign(std::size_t{msg.row_step}, 0);
  uint8_t* out = msg.data.data();
  for (std::size_t i = 0; i < points.size(); ++i, out += msg.point_step) {
    const ScanPoint& p = points[i];
    const float xyzi[4] = {p.x, p.y, p.z, p.intensity};
    std::memcpy(out, xyzi, sizeof(xyzi));
    if (with_ring_and_time) {
      const uint16_t ring = rings ? (*rings)[i] : static_cast<uint16_t>(p.ring < 0 ? 0 : p.ring);
      std::memcpy(out + 16, &p.time, sizeof(float));
      std::memcpy(out + 20, &ring, sizeof(ring));
    }
  }
  return msg;
}

}  // namespace

sensor_msgs::PointCloud2 to_ros(const std::vector<ScanPoint>& points,
                                const std_msgs::Header& header, bool with_ring_and_time) {
  return encode(points, nullptr, header, with_ring_and_time);
}

sensor_msgs::PointCloud2 to_ros(const std::vector<ScanPoint>& points,
                                const std::vector<uint16_t>& rings,
                                const std_msgs::Header& header) {
  return encode(points, &rings, header, true);
}

}  // namespace adaptive_lego_loam::ros_bridge

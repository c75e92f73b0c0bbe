// sensor_msgs/PointCloud2 -> Scan (ros_bridge::from_ros). The input is the message: width,
// height, point_step, row_step (uint32 each), is_bigendian and the number of fields (uint8 each),
// then per field its name length (uint8), name, offset (uint32), datatype (uint8) and count
// (uint32), then the data bytes; all little endian. IoError is the answer to a malformed message.

#include "adaptive_lego_loam/io/io_error.h"
#include "adaptive_lego_loam/ros/cloud_conversions.h"
#include "fuzz_support.h"

using namespace adaptive_lego_loam;

namespace {

sensor_msgs::PointCloud2 message_from(fuzz::ByteReader& input) {
  sensor_msgs::PointCloud2 msg;
  msg.width = input.next<uint32_t>();
  msg.height = input.next<uint32_t>();
  msg.point_step = input.next<uint32_t>();
  msg.row_step = input.next<uint32_t>();
  msg.is_bigendian = input.next<uint8_t>() & 1;
  const uint8_t field_count = input.next<uint8_t>();
  for (int i = 0; i < field_count; ++i) {
    sensor_msgs::PointField field;
    field.name = input.text(input.next<uint8_t>());
    field.offset = input.next<uint32_t>();
    field.datatype = input.next<uint8_t>();
    field.count = input.next<uint32_t>();
    msg.fields.push_back(field);
  }
  const std::string data = input.rest();
  msg.data.assign(data.begin(), data.end());
  return msg;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  fuzz::ByteReader input(data, size);
  const sensor_msgs::PointCloud2 msg = message_from(input);
  try {
    const Scan scan = ros_bridge::from_ros(msg, "/fuzz_points");
    fuzz::check(scan.points.size() == std::size_t{msg.width} * msg.height,
                "a decoded scan has width x height points");
  } catch (const IoError&) {
  }
  return 0;
}

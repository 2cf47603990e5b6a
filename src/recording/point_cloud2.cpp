// sensor_msgs/PointCloud2 in ROS 1 serialisation: header (seq, stamp,
// frame_id), height, width, fields (name, offset, datatype, count),
// is_bigendian, point_step, row_step, data, is_dense. The point data keeps
// the byte order the message states; the rest is little-endian.
#include <l2s/recording/point_cloud2.hpp>

#include <l2s/error.hpp>

#include "detail/point_field_values.hpp"
#include "recording/ros_header.hpp"

#include <algorithm>
#include <limits>

namespace l2s {
namespace {

const char* const kInput = "PointCloud2 message";

/// One field's value in a point, as a double.
double value_of(const PointCloud2Field& f, const std::uint8_t* point, bool swap) {
  return detail::load_point_field(point + f.offset, f.datatype, swap);
}

const PointCloud2Field* field_named(const std::vector<PointCloud2Field>& fields,
                                    std::initializer_list<const char*> names) {
  for (const char* name : names)
    for (const auto& f : fields)
      if (f.name == name) return &f;
  return nullptr;
}

}  // namespace

PointCloud2Sweep decode_point_cloud2(const std::vector<std::uint8_t>& message) {
  PointCloud2Sweep out;
  std::uint32_t point_step = 0, row_step = 0;
  const std::uint8_t* data = nullptr;
  std::uint32_t data_size = 0;
  try {
    detail::ByteReader reader(message.data(), message.size());
    const detail::RosHeader header = detail::read_ros_header(reader);
    out.stamp_ns = header.stamp_ns;
    out.frame_id = header.frame_id;
    out.height = reader.read<std::uint32_t>();
    out.width = reader.read<std::uint32_t>();
    const auto field_count = reader.read<std::uint32_t>();
    if (field_count > reader.remaining() / 13)  // a field takes at least 13 bytes
      throw InputError(kInput, "declares " + std::to_string(field_count) + " fields, more than its bytes hold");
    for (std::uint32_t k = 0; k < field_count; ++k) {
      PointCloud2Field f;
      f.name = reader.read_string();
      f.offset = reader.read<std::uint32_t>();
      f.datatype = reader.read<std::uint8_t>();
      f.count = reader.read<std::uint32_t>();
      out.fields.push_back(f);
    }
    out.big_endian = reader.read<std::uint8_t>() != 0;
    point_step = reader.read<std::uint32_t>();
    row_step = reader.read<std::uint32_t>();
    data_size = reader.read<std::uint32_t>();
    data = reader.take(data_size, "the point data");
  } catch (const detail::ShortBuffer& e) {
    throw InputError(kInput, std::string("cut short: ") + e.what());
  }

  for (const auto& f : out.fields) {
    // sensor_msgs/PointField has no 64-bit integers (PCL's 9 and 10).
    const std::size_t size = f.datatype <= PointCloud2Field::Float64 ? detail::point_field_size(f.datatype) : 0;
    if (size == 0)
      throw InputError(kInput, "field '" + f.name + "' has datatype " + std::to_string(f.datatype) +
                                   ", not one of sensor_msgs/PointField's 1..8");
    if (static_cast<std::uint64_t>(f.offset) + size > point_step)
      throw InputError(kInput, "field '" + f.name + "' at offset " + std::to_string(f.offset) +
                                   " does not fit the point step of " + std::to_string(point_step) + " bytes");
  }
  const PointCloud2Field* x = field_named(out.fields, {"x"});
  const PointCloud2Field* y = field_named(out.fields, {"y"});
  const PointCloud2Field* z = field_named(out.fields, {"z"});
  if (!x || !y || !z) throw InputError(kInput, "has no x, y and z fields");
  if (static_cast<std::uint64_t>(point_step) * out.width > row_step)
    throw InputError(kInput, "a row of " + std::to_string(out.width) + " points of " + std::to_string(point_step) +
                                 " bytes does not fit its row step of " + std::to_string(row_step));
  if (static_cast<std::uint64_t>(row_step) * out.height > data_size)
    throw InputError(kInput, "holds " + std::to_string(data_size) + " data bytes, fewer than " +
                                 std::to_string(out.height) + " rows of " + std::to_string(row_step));

  // Drivers name these differently: Velodyne intensity/ring/time, Ouster
  // t (ns), Livox timestamp (s, absolute), Hesai timestamp, others i, laser_id.
  const PointCloud2Field* intensity = field_named(out.fields, {"intensity", "i"});
  const PointCloud2Field* ring = field_named(out.fields, {"ring", "laser_id"});
  const PointCloud2Field* time = field_named(out.fields, {"time", "t", "timestamp", "time_stamp"});
  const bool swap = out.big_endian;  // hosts are little-endian (checked in the build)
  const std::size_t count = static_cast<std::size_t>(out.width) * out.height;
  if (count == 0) return out;  // an empty sweep (billions of empty rows would still take seconds)
  out.cloud.points.reserve(count);
  if (intensity) out.cloud.intensity.reserve(count);
  if (ring) out.cloud.ring.reserve(count);
  if (time) {
    out.point_times.reserve(count);
    out.time_field = time->name;
  }
  for (std::uint32_t row = 0; row < out.height; ++row) {
    for (std::uint32_t column = 0; column < out.width; ++column) {
      const std::uint8_t* point = data + static_cast<std::size_t>(row) * row_step + static_cast<std::size_t>(column) * point_step;
      out.cloud.points.emplace_back(value_of(*x, point, swap), value_of(*y, point, swap), value_of(*z, point, swap));
      if (intensity) out.cloud.intensity.push_back(static_cast<float>(value_of(*intensity, point, swap)));
      if (ring) {
        // A float ring field may hold anything; NaN and negatives become laser 0.
        const double r = value_of(*ring, point, swap);
        constexpr double kTop = std::numeric_limits<std::uint16_t>::max();
        out.cloud.ring.push_back(static_cast<std::uint16_t>(r > 0.0 ? std::min(r, kTop) : 0.0));
      }
      if (time) out.point_times.push_back(value_of(*time, point, swap));
    }
  }
  return out;
}

}  // namespace l2s

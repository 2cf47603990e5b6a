#pragma once
// sensor_msgs/PointCloud2 messages (ROS 1 serialisation) decoded into a sweep:
// any field layout and numeric type, organised or not, either byte order.

#include <l2s/export.hpp>
#include <l2s/types.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace l2s {

/// A field of a PointCloud2 as the message declares it.
struct PointCloud2Field {
  /// sensor_msgs/PointField's datatype codes.
  enum Type : std::uint8_t { Int8 = 1, UInt8 = 2, Int16 = 3, UInt16 = 4, Int32 = 5, UInt32 = 6, Float32 = 7, Float64 = 8 };
  std::string name;
  std::uint32_t offset = 0;  ///< [bytes] within a point
  std::uint8_t datatype = 0;
  std::uint32_t count = 1;   ///< elements (only the first is read)
};

/// A decoded PointCloud2: its header, its layout and its points.
struct PointCloud2Sweep {
  std::int64_t stamp_ns = 0;  ///< [ns since the epoch] the message header's stamp
  std::string frame_id;
  std::uint32_t height = 1;   ///< rows (1: unorganised)
  std::uint32_t width = 0;    ///< points per row
  std::vector<PointCloud2Field> fields;
  bool big_endian = false;
  /// x y z (NaN kept, as organised clouds mark missing returns), intensity
  /// (field `intensity` or `i`) and ring (`ring` or `laser_id`) when present.
  LidarCloud cloud;
  /// Each point's time field as stored (`time`, `t`, `timestamp` or
  /// `time_stamp`, in that field's own unit: drivers differ), or empty.
  std::vector<double> point_times;
  std::string time_field;     ///< which field point_times came from, or empty
};

/// Decodes one sensor_msgs/PointCloud2 message. Throws InputError("PointCloud2
/// message", fault) when it is cut short, lacks x, y or z, declares a field
/// that does not fit its point step, an unknown datatype, or fewer data bytes
/// than height * row_step.
L2S_EXPORT PointCloud2Sweep decode_point_cloud2(const std::vector<std::uint8_t>& message);

}  // namespace l2s

#pragma once
// Opt-in adapter for code that already uses PCL (e.g. a ROS driver's
// sensor_msgs/PointCloud2 converted with pcl_conversions): turns a PCL cloud
// into the LidarCloud the calibrator takes. Nothing else in l2scalib includes
// this header, so PCL reaches only the users who ask for it; they link PCL
// themselves (find_package(PCL COMPONENTS common)).
//
// Fields: x, y, z (any numeric type); intensity (or i) and ring (or laser_id)
// when present. Organised clouds are flattened; NaN points are kept (the
// calibrator ignores them).

#include <l2s/error.hpp>
#include <l2s/types.hpp>

#include <pcl/PCLPointCloud2.h>
#include <pcl/conversions.h>
#include <pcl/point_cloud.h>

#include <cstdint>
#include <cstring>
#include <string>

namespace l2s::adapters {

namespace pcl_detail {

// Reads one scalar of PCL datatype `type` at `data` as a double.
inline double read_scalar(const std::uint8_t* data, std::uint8_t type) {
  switch (type) {
    case pcl::PCLPointField::INT8: { std::int8_t v; std::memcpy(&v, data, 1); return v; }
    case pcl::PCLPointField::UINT8: return *data;
    case pcl::PCLPointField::INT16: { std::int16_t v; std::memcpy(&v, data, 2); return v; }
    case pcl::PCLPointField::UINT16: { std::uint16_t v; std::memcpy(&v, data, 2); return v; }
    case pcl::PCLPointField::INT32: { std::int32_t v; std::memcpy(&v, data, 4); return v; }
    case pcl::PCLPointField::UINT32: { std::uint32_t v; std::memcpy(&v, data, 4); return v; }
    case pcl::PCLPointField::FLOAT32: { float v; std::memcpy(&v, data, 4); return v; }
    case pcl::PCLPointField::FLOAT64: { double v; std::memcpy(&v, data, 8); return v; }
    default: throw Error("PCL cloud: field of unsupported datatype " + std::to_string(type));
  }
}

inline const pcl::PCLPointField* find_field(const pcl::PCLPointCloud2& cloud, const char* name,
                                            const char* alias = nullptr) {
  for (const auto& field : cloud.fields)
    if (field.name == name || (alias && field.name == alias)) return &field;
  return nullptr;
}

}  // namespace pcl_detail

/// Converts any PCL cloud in its generic form. Throws l2s::Error when x, y or z is missing.
inline LidarCloud from_pcl(const pcl::PCLPointCloud2& cloud) {
  using pcl_detail::find_field;
  using pcl_detail::read_scalar;
  const pcl::PCLPointField* x = find_field(cloud, "x");
  const pcl::PCLPointField* y = find_field(cloud, "y");
  const pcl::PCLPointField* z = find_field(cloud, "z");
  if (!x || !y || !z) throw Error("PCL cloud: no x, y and z fields");
  const pcl::PCLPointField* intensity = find_field(cloud, "intensity", "i");
  const pcl::PCLPointField* ring = find_field(cloud, "ring", "laser_id");

  const std::size_t count = static_cast<std::size_t>(cloud.width) * cloud.height;
  if (cloud.data.size() < count * cloud.point_step) throw Error("PCL cloud: data shorter than width x height");
  LidarCloud out;
  out.points.reserve(count);
  if (intensity) out.intensity.reserve(count);
  if (ring) out.ring.reserve(count);
  for (std::size_t row = 0; row < cloud.height; ++row)
    for (std::size_t column = 0; column < cloud.width; ++column) {
      const std::uint8_t* point = cloud.data.data() + row * cloud.row_step + column * cloud.point_step;
      out.points.emplace_back(read_scalar(point + x->offset, x->datatype),
                              read_scalar(point + y->offset, y->datatype),
                              read_scalar(point + z->offset, z->datatype));
      if (intensity)
        out.intensity.push_back(static_cast<float>(read_scalar(point + intensity->offset, intensity->datatype)));
      if (ring)
        out.ring.push_back(static_cast<std::uint16_t>(read_scalar(point + ring->offset, ring->datatype)));
    }
  return out;
}

/// Converts a typed PCL cloud (pcl::PointXYZI, a driver's PointXYZIR, ...).
template <class PointT>
LidarCloud from_pcl(const pcl::PointCloud<PointT>& cloud) {
  pcl::PCLPointCloud2 generic;
  pcl::toPCLPointCloud2(cloud, generic);
  return from_pcl(generic);
}

}  // namespace l2s::adapters

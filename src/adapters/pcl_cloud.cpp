// PCL point records <-> LidarCloud. One byte-level reader and one writer serve
// the generic (PCLPointCloud2) and the typed (pcl::PointCloud<PointT>) forms:
// both describe a point by PCL's field list, offsets and steps, so a typed
// cloud is read in place rather than copied into a PCLPointCloud2 first.
#include <l2s/adapters/pcl.hpp>

#include <l2s/error.hpp>

#include <pcl/pcl_config.h>

#include "detail/point_field_values.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

namespace l2s::adapters {
namespace {

const char* const kCloud = "PCL cloud";

bool host_big_endian() {
  const std::uint16_t probe = 1;
  std::uint8_t first;
  std::memcpy(&first, &probe, 1);
  return first == 0;
}

// Bytes of one element of a PCL datatype; 0 for an unknown type (the 64-bit
// integers only where this PCL has them).
std::size_t element_size(std::uint8_t type) {
#if PCL_VERSION_COMPARE(<, 1, 12, 0)
  if (type > pcl::PCLPointField::FLOAT64) return 0;
#endif
  return detail::point_field_size(type);
}

// Integers are rounded and clamped: a float intensity 300.4 in a UINT8 field is 255.
template <typename T>
void store_as(std::uint8_t* p, double value) {
  T out;
  if constexpr (std::is_floating_point_v<T>) {
    out = static_cast<T>(value);
  } else {
    const double rounded = std::isnan(value) ? 0.0 : std::round(value);
    const double low = static_cast<double>(std::numeric_limits<T>::lowest());
    const double high = static_cast<double>(std::numeric_limits<T>::max());
    out = rounded <= low ? std::numeric_limits<T>::lowest()
          : rounded >= high ? std::numeric_limits<T>::max()
                            : static_cast<T>(rounded);
  }
  std::memcpy(p, &out, sizeof(T));
}

void store(std::uint8_t* p, std::uint8_t type, double value) {
  switch (type) {
    case pcl::PCLPointField::INT8: return store_as<std::int8_t>(p, value);
    case pcl::PCLPointField::UINT8: return store_as<std::uint8_t>(p, value);
    case pcl::PCLPointField::INT16: return store_as<std::int16_t>(p, value);
    case pcl::PCLPointField::UINT16: return store_as<std::uint16_t>(p, value);
    case pcl::PCLPointField::INT32: return store_as<std::int32_t>(p, value);
    case pcl::PCLPointField::UINT32: return store_as<std::uint32_t>(p, value);
    case pcl::PCLPointField::FLOAT32: return store_as<float>(p, value);
#if PCL_VERSION_COMPARE(>=, 1, 12, 0)
    case pcl::PCLPointField::INT64: return store_as<std::int64_t>(p, value);
    case pcl::PCLPointField::UINT64: return store_as<std::uint64_t>(p, value);
#endif
    default: return store_as<double>(p, value);
  }
}

// The fields the calibrator reads, checked to lie within one record.
struct Wanted {
  const pcl::PCLPointField* xyz[3] = {nullptr, nullptr, nullptr};
  const pcl::PCLPointField* intensity = nullptr;
  const pcl::PCLPointField* ring = nullptr;
};

const pcl::PCLPointField* find(const std::vector<pcl::PCLPointField>& fields, const char* name,
                               const char* alias, std::size_t point_step) {
  for (const auto& field : fields) {
    if (field.name != name && !(alias && field.name == alias)) continue;
    const std::size_t size = element_size(field.datatype);
    if (size == 0)
      throw InputError(kCloud, "field " + field.name + " has datatype " + std::to_string(field.datatype) +
                                   ", not a number type");
    if (static_cast<std::uint64_t>(field.offset) + size > point_step)
      throw InputError(kCloud, "field " + field.name + " at offset " + std::to_string(field.offset) +
                                   " does not fit in a point of " + std::to_string(point_step) + " bytes");
    return &field;
  }
  return nullptr;
}

Wanted find_fields(const std::vector<pcl::PCLPointField>& fields, std::size_t point_step, bool require_xyz) {
  Wanted wanted;
  const char* axes[3] = {"x", "y", "z"};
  for (int axis = 0; axis < 3; ++axis) {
    wanted.xyz[axis] = find(fields, axes[axis], nullptr, point_step);
    if (!wanted.xyz[axis] && require_xyz)
      throw InputError(kCloud, std::string("no field ") + axes[axis] + " (x y z are required)");
  }
  wanted.intensity = find(fields, "intensity", "i", point_step);
  wanted.ring = find(fields, "ring", "laser_id", point_step);
  return wanted;
}

void check_sizes(const PclRecords& r) {
  const std::uint64_t max = std::numeric_limits<std::uint64_t>::max();
  if (r.height != 0 && r.width > max / r.height) throw InputError(kCloud, "width * height overflows");
  if (r.width == 0 || r.height == 0) return;
  if (r.point_step == 0) throw InputError(kCloud, "point_step is 0");
  if (r.width > max / r.point_step || r.row_step < r.width * r.point_step)
    throw InputError(kCloud, "row_step " + std::to_string(r.row_step) + " is shorter than width * point_step (" +
                                 std::to_string(r.width) + " * " + std::to_string(r.point_step) + ")");
  // The last row needs only its records, not a whole row_step.
  if ((r.height - 1) > (max - r.width * r.point_step) / r.row_step ||
      (r.height - 1) * r.row_step + r.width * r.point_step > r.size)
    throw InputError(kCloud, "data holds " + std::to_string(r.size) + " bytes, fewer than " +
                                 std::to_string(r.height) + " rows of " + std::to_string(r.width) + " points need");
}

void check_attributes(const LidarCloud& cloud) {
  if (cloud.has_intensity() && cloud.intensity.size() != cloud.size())
    throw InputError("LidarCloud", std::to_string(cloud.intensity.size()) + " intensity values for " +
                                       std::to_string(cloud.size()) + " points");
  if (cloud.has_ring() && cloud.ring.size() != cloud.size())
    throw InputError("LidarCloud", std::to_string(cloud.ring.size()) + " ring values for " +
                                       std::to_string(cloud.size()) + " points");
}

}  // namespace

LidarCloud from_pcl_records(const PclRecords& r) {
  static const std::vector<pcl::PCLPointField> kNoFields;
  const auto& fields = r.fields ? *r.fields : kNoFields;
  check_sizes(r);
  const Wanted wanted = find_fields(fields, r.point_step, true);
  if (r.width * r.height > 0 && !r.data) throw InputError(kCloud, "no data");
  const bool swap = r.big_endian != host_big_endian();

  LidarCloud out;
  const std::size_t count = static_cast<std::size_t>(r.width * r.height);
  out.points.reserve(count);
  if (wanted.intensity) out.intensity.reserve(count);
  if (wanted.ring) out.ring.reserve(count);
  for (std::uint64_t row = 0; row < r.height; ++row)
    for (std::uint64_t column = 0; column < r.width; ++column) {
      const std::uint8_t* point = r.data + row * r.row_step + column * r.point_step;
      const auto value = [&](const pcl::PCLPointField* f) { return detail::load_point_field(point + f->offset, f->datatype, swap); };
      out.points.emplace_back(value(wanted.xyz[0]), value(wanted.xyz[1]), value(wanted.xyz[2]));
      if (wanted.intensity) out.intensity.push_back(static_cast<float>(value(wanted.intensity)));
      if (wanted.ring) {
        const double ring = value(wanted.ring);
        if (!(ring >= 0.0 && ring <= 65535.0) || ring != std::floor(ring))
          throw InputError(kCloud, "point " + std::to_string(out.points.size() - 1) + " has ring " +
                                       std::to_string(ring) + ", not a laser index in 0..65535");
        out.ring.push_back(static_cast<std::uint16_t>(ring));
      }
    }
  return out;
}

void to_pcl_records(const LidarCloud& cloud, const std::vector<pcl::PCLPointField>& fields,
                    std::uint8_t* data, std::size_t count, std::size_t point_step) {
  check_attributes(cloud);
  const Wanted wanted = find_fields(fields, point_step, true);
  if (count != cloud.size())
    throw InputError(kCloud, std::to_string(count) + " records for " + std::to_string(cloud.size()) + " points");
  for (std::size_t k = 0; k < count; ++k) {
    std::uint8_t* point = data + k * point_step;
    for (int axis = 0; axis < 3; ++axis)
      store(point + wanted.xyz[axis]->offset, wanted.xyz[axis]->datatype, cloud.points[k][axis]);
    if (wanted.intensity && cloud.has_intensity())
      store(point + wanted.intensity->offset, wanted.intensity->datatype, cloud.intensity[k]);
    if (wanted.ring && cloud.has_ring()) store(point + wanted.ring->offset, wanted.ring->datatype, cloud.ring[k]);
  }
}

LidarCloud from_pcl(const pcl::PCLPointCloud2& cloud) {
  PclRecords records;
  records.data = cloud.data.data();
  records.size = cloud.data.size();
  records.fields = &cloud.fields;
  records.width = cloud.width;
  records.height = cloud.height;
  records.point_step = cloud.point_step;
  records.row_step = cloud.row_step;
  records.big_endian = cloud.is_bigendian != 0;
  return from_pcl_records(records);
}

pcl::PCLPointCloud2 to_pcl_cloud2(const LidarCloud& cloud) {
  check_attributes(cloud);
  pcl::PCLPointCloud2 out;
  const auto add_field = [&](const char* name, std::uint8_t type, std::size_t size) {
    pcl::PCLPointField field;
    field.name = name;
    field.offset = static_cast<pcl::uindex_t>(out.point_step);
    field.datatype = type;
    field.count = 1;
    out.fields.push_back(field);
    out.point_step += static_cast<pcl::uindex_t>(size);
  };
  out.point_step = 0;
  for (const char* axis : {"x", "y", "z"}) add_field(axis, pcl::PCLPointField::FLOAT32, 4);
  if (cloud.has_intensity()) add_field("intensity", pcl::PCLPointField::FLOAT32, 4);
  if (cloud.has_ring()) add_field("ring", pcl::PCLPointField::UINT16, 2);
  out.point_step = (out.point_step + 3) / 4 * 4;  // keep every record 4-byte aligned
  out.height = 1;
  out.width = static_cast<pcl::uindex_t>(cloud.size());
  out.row_step = out.width * out.point_step;
  out.is_bigendian = host_big_endian();
  out.data.assign(static_cast<std::size_t>(out.row_step), 0);
  to_pcl_records(cloud, out.fields, out.data.data(), cloud.size(), out.point_step);
  out.is_dense = std::all_of(cloud.points.begin(), cloud.points.end(),
                             [](const Eigen::Vector3d& p) { return p.allFinite(); });
  return out;
}

}  // namespace l2s::adapters

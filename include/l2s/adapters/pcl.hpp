#pragma once
// l2scalib::pcl: PCL clouds to and from the LidarCloud the calibrator takes,
// for code whose sweeps are PCL clouds (a ROS driver's sensor_msgs/PointCloud2
// through pcl_conversions, a PCD file loaded with PCL). Link l2scalib::pcl
// (find_package(l2scalib COMPONENTS pcl)); nothing else in l2scalib includes
// PCL, so only the programs that ask for it see it.
//
// Fields by name: x, y, z (required); intensity (or i); ring (or laser_id).
// Any PCL number type is read; other fields (rgb, normals, PCL's "_" padding,
// a driver's time) are skipped, and so are bytes between fields and at the
// end of a row. Organised clouds (height > 1) come out row by row: ring is
// *not* taken from the row, since drivers order rows differently (Velodyne
// lowest beam first, Ouster highest first); a cloud without a ring field
// gets its rings from elevations in the Calibrator. NaN points are kept.
// Byte order: a PCLPointCloud2 whose is_bigendian differs from the host is
// swapped while it is read; typed clouds are in host order by definition.

#include <l2s/export.hpp>
#include <l2s/types.hpp>

#include <pcl/PCLPointCloud2.h>
#include <pcl/PCLPointField.h>
#include <pcl/common/io.h>
#include <pcl/point_cloud.h>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace l2s::adapters {

/// A block of point records as PCL (and sensor_msgs/PointCloud2) describe
/// them: `height` rows of `width` records of `point_step` bytes, row r
/// starting at data + r * row_step.
struct PclRecords {
  const std::uint8_t* data = nullptr;
  std::size_t size = 0;  ///< [bytes] available at data
  const std::vector<pcl::PCLPointField>* fields = nullptr;
  std::uint64_t width = 0;
  std::uint64_t height = 0;
  std::uint64_t point_step = 0;  ///< [bytes]
  std::uint64_t row_step = 0;    ///< [bytes] >= width * point_step
  bool big_endian = false;       ///< byte order of the data
};

/// Reads records into a LidarCloud (fields as in the header comment). Throws
/// InputError("PCL cloud", ...) when x, y or z is missing, a field it reads
/// does not fit in point_step or has no number type, the sizes do not fit
/// the data, or a ring value is not a laser index (0..65535).
L2S_PCL_EXPORT LidarCloud from_pcl_records(const PclRecords& records);

/// Writes `cloud` into `count` records of `point_step` bytes at `data` (host
/// byte order): x, y, z, and intensity and ring when both the cloud and the
/// fields have them, each converted to its field's type (integers rounded and
/// clamped to the type's range). Bytes of other fields are left as they are.
/// Throws InputError("PCL cloud", ...) when the fields have no x, y or z, a
/// field does not fit in point_step, or `count` differs from the cloud's size;
/// InputError("LidarCloud", ...) when intensity or ring has another length
/// than the points.
L2S_PCL_EXPORT void to_pcl_records(const LidarCloud& cloud, const std::vector<pcl::PCLPointField>& fields,
                                   std::uint8_t* data, std::size_t count, std::size_t point_step);

/// Converts a cloud in PCL's generic form (any fields, organised or not,
/// either byte order). Throws as from_pcl_records.
L2S_PCL_EXPORT LidarCloud from_pcl(const pcl::PCLPointCloud2& cloud);

/// A PCLPointCloud2 of one row: x y z as FLOAT32, then intensity (FLOAT32)
/// and ring (UINT16) when the cloud has them; host byte order; is_dense when
/// every point is finite. Throws InputError("LidarCloud", ...) when intensity
/// or ring has another length than the points.
L2S_PCL_EXPORT pcl::PCLPointCloud2 to_pcl_cloud2(const LidarCloud& cloud);

/// Converts a typed PCL cloud (pcl::PointXYZ, pcl::PointXYZI, a driver's
/// PointXYZIR, ...) without an intermediate copy. A cloud whose width *
/// height is not its point count (points appended to cloud.points directly)
/// is read as one row. Throws InputError when PointT has no x, y or z.
template <class PointT>
LidarCloud from_pcl(const pcl::PointCloud<PointT>& cloud) {
  const std::vector<pcl::PCLPointField> fields = pcl::getFields<PointT>();
  PclRecords records;
  records.data = reinterpret_cast<const std::uint8_t*>(cloud.points.data());
  records.size = cloud.points.size() * sizeof(PointT);
  records.fields = &fields;
  records.width = cloud.width;
  records.height = cloud.height;
  records.point_step = sizeof(PointT);
  records.row_step = static_cast<std::uint64_t>(cloud.width) * sizeof(PointT);
  records.big_endian = false;
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
  records.big_endian = true;
#endif
  if (records.width * records.height != cloud.points.size()) {
    // An unorganised cloud whose width was not kept up to date: read it as one row.
    records.width = cloud.points.size();
    records.height = cloud.points.empty() ? 0 : 1;
    records.row_step = records.size;
  }
  return from_pcl_records(records);
}

/// Converts to a typed PCL cloud of one row; fields of PointT other than x y
/// z intensity ring keep PointT's defaults. is_dense when every point is
/// finite. Throws as to_pcl_records.
template <class PointT>
pcl::PointCloud<PointT> to_pcl(const LidarCloud& cloud) {
  pcl::PointCloud<PointT> out;
  out.resize(cloud.size());  // width = size, height = 1
  to_pcl_records(cloud, pcl::getFields<PointT>(), reinterpret_cast<std::uint8_t*>(out.points.data()),
                 out.points.size(), sizeof(PointT));
  out.is_dense = true;
  for (const auto& p : cloud.points)
    if (!p.allFinite()) {
      out.is_dense = false;
      break;
    }
  return out;
}

}  // namespace l2s::adapters

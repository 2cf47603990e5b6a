// Feeds pcl::PointCloud sweeps to the Calibrator, as a ROS node would with a
// driver's clouds (here they are loaded from a dataset's PCD files with PCL):
// l2s::adapters::from_pcl converts each sweep in place, without a copy
// through PCLPointCloud2, and to_pcl hands a result back to PCL (the last
// sweep moved into the camera frame, written as a PCD file).
//   03_calibrate_pcl_clouds DATASET [SWEEP_IN_CAMERA_FRAME.pcd]
// Needs l2scalib's pcl component: find_package(l2scalib COMPONENTS pcl).
#define PCL_NO_PRECOMPILE
#include <l2s/adapters/pcl.hpp>
#include <l2s/calibrator.hpp>
#include <l2s/error.hpp>
#include <l2s/io/dataset.hpp>
#include <l2s/io/image_io.hpp>

#include <pcl/io/pcd_io.h>
#include <pcl/point_types.h>

#include <iostream>

// The point of the ROS velodyne driver. A sweep without a ring field would
// load with ring 0 everywhere: use a type without `ring` (pcl::PointXYZI) for
// such lidars, and the Calibrator recovers the rings from elevations.
struct VelodynePoint {
  PCL_ADD_POINT4D;
  float intensity;
  std::uint16_t ring;
  PCL_MAKE_ALIGNED_OPERATOR_NEW
} EIGEN_ALIGN16;
POINT_CLOUD_REGISTER_POINT_STRUCT(VelodynePoint, (float, x, x)(float, y, y)(float, z, z)(float, intensity,
                                                                                       intensity)(
                                                     std::uint16_t, ring, ring))

int main(int argc, char** argv) {
  if (argc < 2 || argc > 3) {
    std::cerr << "usage: " << argv[0] << " DATASET [SWEEP_IN_CAMERA_FRAME.pcd]\n";
    return 2;
  }
  try {
    // The dataset gives the cameras, the board and the file names; the sweeps
    // themselves come from PCL, as they would from a driver.
    const auto dataset = l2s::io::Dataset::open(argv[1]);
    l2s::Calibrator calibrator(dataset.cameras(), dataset.target());
    pcl::PointCloud<VelodynePoint> sweep;
    for (const std::string& stem : dataset.stems()) {
      if (pcl::io::loadPCDFile(dataset.lidar_path(stem), sweep) != 0) {
        std::cerr << dataset.lidar_path(stem) << ": PCL cannot read it\n";
        return 1;
      }
      const auto left = l2s::io::read_image(dataset.left_path(stem));
      const auto right = l2s::io::read_image(dataset.right_path(stem));
      const auto report = calibrator.add(l2s::adapters::from_pcl(sweep), left, right, stem);
      if (!report.used())
        std::cout << stem << ": " << (report.lidar.found ? report.camera.reason : report.lidar.reason) << "\n";
    }
    const auto result = calibrator.result();
    if (!result.found) {
      std::cerr << "calibration failed: " << result.reason << "\n";
      return 1;
    }
    std::cout << "T_lidar_camera =\n" << result.T_lidar_camera.matrix() << "\n";

    if (argc == 3) {
      l2s::LidarCloud in_camera = l2s::adapters::from_pcl(sweep);
      const Eigen::Isometry3d T_camera_lidar = result.T_lidar_camera.inverse();
      for (auto& point : in_camera.points) point = T_camera_lidar * point;
      pcl::io::savePCDFileBinary(argv[2], l2s::adapters::to_pcl<VelodynePoint>(in_camera));
      std::cout << "wrote " << argv[2] << "\n";
    }
  } catch (const l2s::Error& error) {
    std::cerr << "error: " << error.what() << "\n";
    return 1;
  }
  return 0;
}

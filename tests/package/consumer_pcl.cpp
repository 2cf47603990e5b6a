// l2scalib::pcl from outside: a pcl::PointCloud to LidarCloud and back.
#include <l2s/adapters/pcl.hpp>

#include <pcl/point_types.h>

#include <cstdio>

int main() {
  pcl::PointCloud<pcl::PointXYZI> cloud;
  for (int i = 0; i < 10; ++i) {
    pcl::PointXYZI point(static_cast<float>(i));
    point.x = 1.0f + i;
    cloud.push_back(point);
  }
  const l2s::LidarCloud sweep = l2s::adapters::from_pcl(cloud);
  const auto back = l2s::adapters::to_pcl<pcl::PointXYZI>(sweep);
  std::printf("pcl round trip: %zu points\n", back.size());
  return back.size() == 10 && back[9].x == 10.0f && back[9].intensity == 9.0f ? 0 : 1;
}

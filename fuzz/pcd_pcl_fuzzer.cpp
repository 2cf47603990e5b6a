// PCL's PCD reader (pcl::PCDReader into a PCLPointCloud2) on whole PCD files,
// as the PCD fuzz targets feed ours. Kept to measure, not to guard: it is the
// evidence for reading PCD files with our own code (README, "PCD files").
// A crash, a sanitizer report in code we compile, an exception or an
// allocation past -rss_limit_mb is a finding; a negative return code is not.
#include "fuzz_input.hpp"

#include <pcl/PCLPointCloud2.h>
#include <pcl/console/print.h>
#include <pcl/io/pcd_io.h>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const bool quiet = [] {
    pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
    return true;
  }();
  (void)quiet;
  const std::string& path = l2s::fuzz::write_scratch(data, size, ".pcd");
  pcl::PCLPointCloud2 cloud;
  pcl::PCDReader reader;
  (void)reader.read(path, cloud);
  return 0;
}

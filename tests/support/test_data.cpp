#include "support/test_data.hpp"

#include <l2s/metrics.hpp>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

namespace fs = std::filesystem;

namespace l2s::test {

TempDir::TempDir() {
  static std::atomic<int> counter{0};
  const char* root = std::getenv("L2S_TEST_TMP");
  const fs::path base = root ? fs::path(root) : fs::temp_directory_path() / "l2s_tests";
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::ostringstream name;
  name << (info ? std::string(info->test_suite_name()) + "." + info->name() : "test") << "."
       << ::getpid() << "." << counter++;
  // Parameterised test names hold '/', which would nest folders.
  std::string leaf = name.str();
  std::replace(leaf.begin(), leaf.end(), '/', '_');
  path_ = (base / leaf).string();
  fs::remove_all(path_);
  fs::create_directories(path_);
}

TempDir::~TempDir() {
  std::error_code ignored;
  fs::remove_all(path_, ignored);
}

void write_text(const std::string& path, const std::string& content) {
  std::ofstream out(path, std::ios::binary);
  out << content;
}

std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

std::string dataset_checker() { return std::string(L2S_SHARED_DIR) + "/tools/check_dataset.py"; }

std::string dataset_checker_missing() {
  if (!fs::exists(dataset_checker())) return "needs " + dataset_checker();
  if (!fs::exists("/usr/bin/python3")) return "needs /usr/bin/python3";
  if (std::system("/usr/bin/python3 -c 'import yaml' >/dev/null 2>&1") != 0) return "needs python3-yaml";
  return "";
}

bool shared_required() {
  const char* value = std::getenv("L2S_REQUIRE_SHARED");
  return value && std::string(value) == "1";
}

::testing::AssertionResult pose_near(const Eigen::Isometry3d& T, const Eigen::Isometry3d& T_true,
                                     double rotation_deg, double translation_m) {
  const PoseError error = pose_error(T, T_true);
  const double rotation_error_deg = error.rotation * 180.0 / M_PI;
  if (rotation_error_deg <= rotation_deg && error.translation <= translation_m)
    return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << "pose error e_r = " << rotation_error_deg << " deg (limit " << rotation_deg
         << "), e_t = " << error.translation << " m (limit " << translation_m << ")\nestimate:\n"
         << T.matrix() << "\ntruth:\n"
         << T_true.matrix();
}

}  // namespace l2s::test

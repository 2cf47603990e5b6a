#pragma once
// Helpers shared by the tests: temporary folders and pose assertions.

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <string>

namespace l2s::test {

/// A fresh, empty folder for one test, removed when the object goes away.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::string& path() const { return path_; }
  std::string file(const std::string& name) const { return path_ + "/" + name; }

 private:
  std::string path_;
};

/// Writes `content` to `path` verbatim (for hand-made bad input files).
void write_text(const std::string& path, const std::string& content);

/// Reads a whole file as bytes.
std::string read_bytes(const std::string& path);

::testing::AssertionResult pose_near(const Eigen::Isometry3d& T, const Eigen::Isometry3d& T_true,
                                     double rotation_deg, double translation_m);

}  // namespace l2s::test

/// EXPECT_POSE_NEAR(T, T_true, rot_deg, trans_m): rotation and translation errors within bounds.
#define EXPECT_POSE_NEAR(T, T_true, rot_deg, trans_m) \
  EXPECT_TRUE(::l2s::test::pose_near((T), (T_true), (rot_deg), (trans_m)))

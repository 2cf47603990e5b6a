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

/// The dataset contract's checker, L2S_SHARED_DIR/tools/check_dataset.py, and
/// why it cannot run here ("" when it can: the script, /usr/bin/python3 and
/// its yaml module are there).
std::string dataset_checker();
std::string dataset_checker_missing();

/// True when the environment sets L2S_REQUIRE_SHARED=1 (CI does): a test that
/// needs ../shared must then fail rather than skip without it.
bool shared_required();

::testing::AssertionResult pose_near(const Eigen::Isometry3d& T, const Eigen::Isometry3d& T_true,
                                     double rotation_deg, double translation_m);

}  // namespace l2s::test

/// Skips the test when the dataset checker cannot run, or fails it when
/// L2S_REQUIRE_SHARED=1 says it must run.
#define L2S_NEED_DATASET_CHECKER()                                                            \
  do {                                                                                        \
    const std::string l2s_missing = ::l2s::test::dataset_checker_missing();                  \
    if (!l2s_missing.empty()) {                                                               \
      if (::l2s::test::shared_required()) FAIL() << "L2S_REQUIRE_SHARED=1: " << l2s_missing; \
      GTEST_SKIP() << l2s_missing;                                                            \
    }                                                                                         \
  } while (false)

/// EXPECT_POSE_NEAR(T, T_true, rot_deg, trans_m): rotation and translation errors within bounds.
#define EXPECT_POSE_NEAR(T, T_true, rot_deg, trans_m) \
  EXPECT_TRUE(::l2s::test::pose_near((T), (T_true), (rot_deg), (trans_m)))

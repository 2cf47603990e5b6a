// The bad-input table of docs/library.md, one test per row: each public entry point
// given a typical fault answers with the documented error type and a message
// that names the file, field or input. Keep the two in step: a row without a
// test here (or a test without a row) is a bug of the table.

#include <l2s/calibrator.hpp>
#include <l2s/error.hpp>
#include <l2s/io/calibrator_yaml.hpp>
#include <l2s/io/camera_yaml.hpp>
#include <l2s/io/dataset.hpp>
#include <l2s/io/pcd.hpp>
#include <l2s/io/target_yaml.hpp>
#include <l2s/io/transform_yaml.hpp>

#include "support/test_data.hpp"

#include <gtest/gtest.h>

#include <filesystem>

namespace l2s {
namespace {

namespace fs = std::filesystem;

// Runs `statement`, expects an exception of type E whose message starts with
// `start` and contains `part`.
#define EXPECT_ERROR(statement, E, start, part)                                            \
  do {                                                                                     \
    try {                                                                                  \
      statement;                                                                           \
      ADD_FAILURE() << "no exception from " #statement;                                    \
    } catch (const E& error) {                                                             \
      const std::string message = error.what();                                            \
      EXPECT_EQ(message.rfind(start, 0), 0u) << message << "\n  should start with " << start; \
      EXPECT_NE(message.find(part), std::string::npos) << message << "\n  should hold " << part; \
    }                                                                                      \
  } while (false)

const char* const kPcdHeader =
    "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 2\nHEIGHT 1\nPOINTS 2\n";

std::string camera_yaml(double fx, double tx, int width = 640) {
  return "image_width: " + std::to_string(width) +
         "\nimage_height: 480\nprojection_matrix:\n  rows: 3\n  cols: 4\n  data: [" +
         std::to_string(fx) + ", 0, 320, " + std::to_string(tx) + ", 0, " + std::to_string(fx) +
         ", 240, 0, 0, 0, 1, 0]\n";
}

StereoCamera rig(double baseline = 0.12) {
  StereoCamera cameras;
  cameras.left = CameraInfo::ideal("left", 640, 480, 500.0, 320.0, 240.0);
  cameras.right = CameraInfo::ideal("right", 640, 480, 500.0, 320.0, 240.0, baseline);
  return cameras;
}

class BadInput : public ::testing::Test {
 protected:
  std::string file(const std::string& name, const std::string& content) {
    const std::string path = dir_.file(name);
    test::write_text(path, content);
    return path;
  }
  test::TempDir dir_;
};

// --- PCD sweeps: io::read_pcd, io::write_pcd -------------------------------

TEST_F(BadInput, PcdMissingFile) {
  const std::string path = dir_.file("none.pcd");
  EXPECT_ERROR(io::read_pcd(path), FileError, path, "missing file");
}

TEST_F(BadInput, PcdWithoutDataLine) {
  const std::string path = file("a.pcd", "VERSION 0.7\nFIELDS x y z\n");
  EXPECT_ERROR(io::read_pcd(path), FileError, path, "not a PCD file");
}

TEST_F(BadInput, PcdWithoutZ) {
  const std::string path =
      file("a.pcd", "FIELDS x y\nSIZE 4 4\nTYPE F F\nWIDTH 1\nPOINTS 1\nDATA ascii\n1 2\n");
  EXPECT_ERROR(io::read_pcd(path), FileError, path, "no field z");
}

TEST_F(BadInput, PcdPointsDisagreeWithWidthTimesHeight) {
  const std::string path = file("a.pcd", "FIELDS x y z\nSIZE 4 4 4\nWIDTH 2\nHEIGHT 2\nPOINTS 3\nDATA ascii\n");
  EXPECT_ERROR(io::read_pcd(path), FileError, path, "POINTS 3 != WIDTH * HEIGHT");
}

TEST_F(BadInput, PcdBinaryTruncated) {
  const std::string path = file("a.pcd", std::string(kPcdHeader) + "DATA binary\n" + std::string(20, '\0'));
  EXPECT_ERROR(io::read_pcd(path), FileError, path, "truncated");
}

TEST_F(BadInput, PcdCompressedCorrupt) {
  // Sizes that fit the file, then a back-reference before the start of the output.
  const std::string data = std::string("\x04\0\0\0\x18\0\0\0", 8) + "\xe0\xff\x01\x02";
  const std::string path = file("a.pcd", std::string(kPcdHeader) + "DATA binary_compressed\n" + data);
  EXPECT_ERROR(io::read_pcd(path), FileError, path, "corrupt");
}

TEST_F(BadInput, PcdAsciiValueNotANumber) {
  const std::string path = file("a.pcd", std::string(kPcdHeader) + "DATA ascii\n1 2 3\n1 two 3\n");
  EXPECT_ERROR(io::read_pcd(path), FileError, path, "'two' is not a number (field y)");
}

TEST_F(BadInput, PcdRingNotALaserIndex) {
  const std::string path = file("a.pcd", "FIELDS x y z ring\nSIZE 4 4 4 4\nTYPE F F F F\nWIDTH 1\nPOINTS 1\n"
                                         "DATA ascii\n1 2 3 -1\n");
  EXPECT_ERROR(io::read_pcd(path), FileError, path, "not a laser index");
}

TEST_F(BadInput, PcdWriteIntensityOfTheWrongLength) {
  LidarCloud cloud;
  cloud.points.assign(3, Eigen::Vector3d::Zero());
  cloud.intensity.assign(2, 1.0f);
  EXPECT_ERROR(io::write_pcd(dir_.file("w.pcd"), cloud), ParamError, "parameter cloud.intensity",
               "2 values for 3 points");
}

// --- camera_info YAML: io::read_camera_info, io::read_stereo_camera ---------

TEST_F(BadInput, CameraInfoMissingImageWidth) {
  const std::string path = file("left.yaml", "image_height: 480\n");
  EXPECT_ERROR(io::read_camera_info(path), FileError, path, "missing key image_width");
}

TEST_F(BadInput, CameraInfoProjectionNot3x4) {
  const std::string path =
      file("left.yaml", "image_width: 640\nimage_height: 480\nprojection_matrix: {rows: 3, cols: 3, "
                        "data: [1, 0, 0, 0, 1, 0, 0, 0, 1]}\n");
  EXPECT_ERROR(io::read_camera_info(path), FileError, path, "projection_matrix: expected 3x4");
}

TEST_F(BadInput, CameraInfoNonPositiveFocalLength) {
  const std::string path = file("left.yaml", camera_yaml(0.0, 0.0));
  EXPECT_ERROR(io::read_camera_info(path), FileError, path, "fx and fy must be positive");
}

TEST_F(BadInput, CameraInfoMalformedYaml) {
  const std::string path = file("left.yaml", "image_width: [640\n");
  EXPECT_ERROR(io::read_camera_info(path), FileError, path, "malformed YAML");
}

TEST_F(BadInput, StereoPairWithNonPositiveBaseline) {
  const std::string left = file("left.yaml", camera_yaml(500.0, 0.0));
  const std::string right = file("right.yaml", camera_yaml(500.0, 60.0));  // -P[0][3]/fx < 0
  EXPECT_ERROR(io::read_stereo_camera(left, right), FileError, right, "must be positive");
}

TEST_F(BadInput, StereoPairOfDifferentSizes) {
  const std::string left = file("left.yaml", camera_yaml(500.0, 0.0));
  const std::string right = file("right.yaml", camera_yaml(500.0, -60.0, 800));
  EXPECT_ERROR(io::read_stereo_camera(left, right), FileError, right, "differs from");
}

// --- target.yaml: io::read_target ------------------------------------------

TEST_F(BadInput, TargetHolesDoNotFit) {
  const std::string path = file("target.yaml", "hole_radius: 0.3\n");
  EXPECT_ERROR(io::read_target(path), FileError, path, "parameter hole_spacing_x: holes overlap");
}

TEST_F(BadInput, TargetValueNotANumber) {
  const std::string path = file("target.yaml", "board_width: wide\n");
  EXPECT_ERROR(io::read_target(path), FileError, path, "board_width: expected a number");
}

// --- Calibrator params YAML: io::read_calibrator_params ---------------------

TEST_F(BadInput, ParamsUnknownKey) {
  const std::string path = file("p.yaml", "lidar_plane:\n  distance_treshold: 0.1\n");
  EXPECT_ERROR(io::read_calibrator_params(path), FileError, path, "unknown key lidar_plane.distance_treshold");
}

TEST_F(BadInput, ParamsValueOfTheWrongType) {
  const std::string path = file("p.yaml", "accumulator:\n  min_frames: many\n");
  EXPECT_ERROR(io::read_calibrator_params(path), FileError, path, "key accumulator.min_frames: not a valid integer");
}

TEST_F(BadInput, ParamsValueOutOfRange) {
  const std::string path = file("p.yaml", "accumulator:\n  min_frames: 0\n");
  EXPECT_ERROR(io::read_calibrator_params(path), FileError, path, "parameter accumulator.min_frames");
}

TEST_F(BadInput, ParamsUnknownPreset) {
  const std::string path = file("p.yaml", "preset: best\n");
  EXPECT_ERROR(io::read_calibrator_params(path), FileError, path, "unknown preset 'best'");
}

// --- Transform YAML: io::read_transform ------------------------------------

TEST_F(BadInput, TransformMissingKey) {
  const std::string path = file("t.yaml", "T_other: {rows: 1, cols: 1, data: [1]}\n");
  EXPECT_ERROR(io::read_transform(path), FileError, path, "missing key T_lidar_camera");
}

TEST_F(BadInput, TransformRotationNotOrthonormal) {
  const std::string path =
      file("t.yaml", "T_lidar_camera: {rows: 4, cols: 4, data: [2, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]}\n");
  EXPECT_ERROR(io::read_transform(path), FileError, path, "rotation is not orthonormal");
}

TEST_F(BadInput, TransformLastRowNotHomogeneous) {
  const std::string path =
      file("t.yaml", "T_lidar_camera: {rows: 4, cols: 4, data: [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 1, 1]}\n");
  EXPECT_ERROR(io::read_transform(path), FileError, path, "last row must be 0 0 0 1");
}

// --- Dataset folders: io::Dataset ------------------------------------------

TEST_F(BadInput, DatasetMissingFolder) {
  const std::string path = dir_.file("nowhere");
  EXPECT_ERROR(io::Dataset::open(path), FileError, path, "no such dataset folder");
}

TEST_F(BadInput, DatasetStemsDiffer) {
  const std::string folder = dir_.file("ds");
  io::DatasetWriter writer(folder, rig(), Target{});
  io::Frame frame;
  frame.stem = "000000";
  frame.lidar.points.assign(3, Eigen::Vector3d::UnitX());
  frame.left = Image(640, 480);
  frame.right = Image(640, 480);
  writer.write(frame);
  fs::remove(folder + "/left/000000.png");
  EXPECT_ERROR(io::Dataset::open(folder), FileError, folder, "000000 (no left/000000.png)");
}

// --- The Calibrator: construction, add(), the result file ------------------

TEST_F(BadInput, CalibratorRigWithNonPositiveBaseline) {
  EXPECT_ERROR(Calibrator(rig(-0.12), Target{}), ParamError, "parameter cameras.right.projection_matrix",
               "baseline");
}

TEST_F(BadInput, CalibratorInvalidParams) {
  Calibrator::Params params;
  params.accumulator.min_frames = 0;
  EXPECT_ERROR(Calibrator(rig(), Target{}, params), ParamError, "parameter accumulator.min_frames", "");
}

TEST_F(BadInput, CalibratorImpossibleTarget) {
  Target target;
  target.hole_radius = 0.3;
  EXPECT_ERROR(Calibrator(rig(), target), ParamError, "parameter hole_spacing_x", "holes overlap");
}

TEST_F(BadInput, AddImageOfTheWrongSize) {
  Calibrator calibrator(rig(), Target{});
  EXPECT_ERROR(calibrator.add(LidarCloud{}, Image(64, 48), Image(640, 480)), InputError, "left image",
               "64x48 px, but the left camera is 640x480 px");
  EXPECT_EQ(calibrator.result().frames_added, 0) << "nothing may be recorded for a rejected frame";
}

TEST_F(BadInput, AddEmptyImage) {
  Calibrator calibrator(rig(), Target{});
  EXPECT_ERROR(calibrator.add(LidarCloud{}, Image(640, 480), Image{}), InputError, "right image", "empty");
}

TEST_F(BadInput, AddImageWithTwoChannels) {
  Calibrator calibrator(rig(), Target{});
  EXPECT_ERROR(calibrator.camera_branch(Image(640, 480, 2), Image(640, 480)), InputError, "left image",
               "2 channels");
}

// Bad sweeps are reported, never thrown: the frame's lidar branch says why.
TEST_F(BadInput, AddSweepWithIntensityOfTheWrongLength) {
  Calibrator calibrator(rig(), Target{});
  LidarCloud sweep;
  sweep.points.assign(100, Eigen::Vector3d(3.0, 0.0, 0.0));
  sweep.intensity.assign(99, 1.0f);
  const FrameReport report = calibrator.add(sweep, BranchReport{});
  EXPECT_FALSE(report.lidar.found);
  EXPECT_EQ(report.lidar.failed_stage, "input");
  EXPECT_EQ(report.lidar.reason, "intensity field has a different length than the points");
}

TEST_F(BadInput, AddSweepWithRingOfTheWrongLength) {
  Calibrator calibrator(rig(), Target{});
  LidarCloud sweep;
  sweep.points.assign(100, Eigen::Vector3d(3.0, 0.0, 0.0));
  sweep.ring.assign(101, 0);
  const FrameReport report = calibrator.add(sweep, BranchReport{});
  EXPECT_EQ(report.lidar.failed_stage, "input");
  EXPECT_EQ(report.lidar.reason, "ring field has a different length than the points");
}

TEST_F(BadInput, AddEmptySweep) {
  Calibrator calibrator(rig(), Target{});
  const FrameReport report = calibrator.add(LidarCloud{}, BranchReport{});
  EXPECT_EQ(report.lidar.failed_stage, "input");
  EXPECT_EQ(report.lidar.reason, "empty sweep");
}

TEST_F(BadInput, ResultFileOfAFailedCalibration) {
  Calibrator calibrator(rig(), Target{});
  calibrator.add(LidarCloud{}, BranchReport{});
  const Calibrator::Result result = calibrator.result();
  ASSERT_FALSE(result.found);
  const std::string path = file("calibration.yaml", "an earlier result\n");
  EXPECT_ERROR(io::write_calibration_result(path, result), InputError, "result: the calibration failed",
               result.reason);
  EXPECT_EQ(test::read_bytes(path), "an earlier result\n") << "an existing file must stay as it was";
  const std::string fresh = dir_.file("fresh.yaml");
  EXPECT_THROW(io::write_calibration_result(fresh, result), InputError);
  EXPECT_FALSE(fs::exists(fresh));
}

}  // namespace
}  // namespace l2s

// Dataset folders: DatasetWriter output read back by Dataset and by
// tools/check_dataset.py, and every way a folder can break the contract.
#include <l2s/error.hpp>
#include <l2s/io/camera_yaml.hpp>
#include <l2s/io/dataset.hpp>
#include <l2s/io/dataset_yaml.hpp>
#include <l2s/io/image_io.hpp>
#include <l2s/io/pcd.hpp>
#include <l2s/io/target_yaml.hpp>

#include "io_test_helpers.hpp"
#include "support/laser_sweep.hpp"
#include "support/test_data.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>

namespace fs = std::filesystem;

namespace l2s::io {
namespace {

constexpr int kWidth = 64, kHeight = 48;

StereoCamera cameras() {
  return {CameraInfo::ideal("left", kWidth, kHeight, 50.0, 31.5, 23.5),
          CameraInfo::ideal("right", kWidth, kHeight, 50.0, 31.5, 23.5, 0.12)};
}

// A 16-beam sweep (2 deg apart) whose ring field is the truth.
LidarCloud sweep(int seed) {
  LidarCloud cloud;
  for (int beam = 0; beam < 16; ++beam)
    for (int k = 0; k < 90; ++k) {
      const double e = (-15.0 + 2.0 * beam) * M_PI / 180.0, a = (4.0 * k + seed) * M_PI / 180.0;
      const double r = 5.0 + 0.1 * ((k * 7 + beam) % 13);
      cloud.points.emplace_back(r * std::cos(e) * std::cos(a), r * std::cos(e) * std::sin(a),
                                r * std::sin(e));
      cloud.intensity.push_back(static_cast<float>(k % 50));
      cloud.ring.push_back(static_cast<std::uint16_t>(beam));
    }
  cloud.points[5] = Eigen::Vector3d::Constant(NAN);
  return cloud;
}

Frame frame(const std::string& stem, int seed) {
  Frame f;
  f.stem = stem;
  f.lidar = sweep(seed);
  f.left = Image(kWidth, kHeight, 1, static_cast<std::uint8_t>(seed));
  f.right = Image(kWidth, kHeight, 3, static_cast<std::uint8_t>(seed + 1));
  f.left.at(3, 4) = 200;
  return f;
}

Eigen::Isometry3d pose() {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  T.translation() << 0.2, -0.1, 0.05;
  return T;
}

// Writes three frames (one per PCD encoding) and the ground truth.
std::string write_dataset(const test::TempDir& dir, const Target& target = Target::paper2017()) {
  const std::string folder = dir.file("data");
  const DatasetWriter writer(folder, cameras(), target);
  writer.write(frame("000002", 2), PcdEncoding::BinaryCompressed);
  writer.write(frame("000000", 0), PcdEncoding::Ascii);
  writer.write(frame("000001", 1));
  writer.write_ground_truth(pose());
  return folder;
}

void expect_same_frame(const Frame& read, const Frame& written) {
  EXPECT_EQ(read.stem, written.stem);
  EXPECT_FALSE(read.rings_recovered());
  EXPECT_EQ(read.ring_source, RingSource::Field);
  EXPECT_FALSE(read.ring_recovery.has_value());
  ASSERT_EQ(read.lidar.size(), written.lidar.size());
  // Compared as float32, the type in the file (not as double(float(x)): GCC 12
  // -O2 vectorizes that round trip away for pairs of coordinates).
  for (std::size_t i = 0; i < read.lidar.size(); ++i) {
    const Eigen::Vector3f expected = written.lidar.points[i].cast<float>();
    if (expected.allFinite()) {
      EXPECT_EQ(read.lidar.points[i].cast<float>(), expected) << i;
    } else {
      EXPECT_FALSE(read.lidar.points[i].allFinite()) << i;
    }
  }
  EXPECT_EQ(read.lidar.intensity, written.lidar.intensity);
  EXPECT_EQ(read.lidar.ring, written.lidar.ring);
  EXPECT_EQ(read.left.pixels, written.left.pixels);
  EXPECT_EQ(read.left.channels, 1);
  EXPECT_EQ(read.right.pixels, written.right.pixels);
  EXPECT_EQ(read.right.channels, 3);
}

TEST(DatasetWriter, WritesFolderThatDatasetReadsBack) {
  test::TempDir dir;
  const std::string folder = write_dataset(dir);
  const Dataset dataset = Dataset::open(folder);
  EXPECT_EQ(dataset.stems(), (std::vector<std::string>{"000000", "000001", "000002"}));
  EXPECT_EQ(dataset.cameras().left.projection_matrix, cameras().left.projection_matrix);
  EXPECT_EQ(dataset.cameras().right.projection_matrix, cameras().right.projection_matrix);
  EXPECT_DOUBLE_EQ(dataset.cameras().baseline(), 0.12);
  EXPECT_TRUE(dataset.has_target_file());
  EXPECT_EQ(dataset.target().hole_spacing_x, Target::paper2017().hole_spacing_x);
  EXPECT_EQ(dataset.target().board_width, Target::paper2017().board_width);
  for (std::size_t i = 0; i < dataset.size(); ++i)
    expect_same_frame(dataset.load(i), frame(dataset.stems()[i], static_cast<int>(i)));
  ASSERT_TRUE(dataset.ground_truth().has_value());
  EXPECT_EQ(dataset.ground_truth()->matrix(), pose().matrix());
  EXPECT_THROW(dataset.load(3), ParamError);
}

TEST(DatasetWriter, WritesTheSameBytesTwice) {
  test::TempDir a, b;
  const std::string first = write_dataset(a), second = write_dataset(b);
  for (const char* file :
       {"left.yaml", "right.yaml", "target.yaml", "ground_truth.yaml", "lidar/000000.pcd",
        "lidar/000001.pcd", "lidar/000002.pcd", "left/000001.png", "right/000002.png"})
    EXPECT_EQ(test::read_bytes(first + "/" + file), test::read_bytes(second + "/" + file)) << file;
}

TEST(DatasetWriter, OutputPassesCheckDatasetScript) {
  L2S_NEED_DATASET_CHECKER();
  const std::string script = test::dataset_checker();
  test::TempDir dir;
  const std::string folder = write_dataset(dir);
  const std::string command = "/usr/bin/python3 " + script + " " + folder + " --lidar-beams 16 > " +
                              dir.file("check.log") + " 2>&1";
  EXPECT_EQ(std::system(command.c_str()), 0) << test::read_bytes(dir.file("check.log"));
  // The script must be able to fail, too: a dataset without frames.
  fs::remove_all(folder + "/lidar");
  fs::create_directories(folder + "/lidar");
  EXPECT_NE(std::system(command.c_str()), 0);
}

TEST(DatasetWriter, RefusesWhatTheReaderWouldReject) {
  test::TempDir dir;
  StereoCamera swapped{cameras().right, cameras().left};
  EXPECT_THROW(DatasetWriter(dir.file("a"), swapped, Target{}), FileError);
  Target impossible;
  impossible.hole_radius = 1.0;
  EXPECT_THROW(DatasetWriter(dir.file("b"), cameras(), impossible), ParamError);

  const DatasetWriter writer(dir.file("c"), cameras(), Target{});
  Frame f = frame("000000", 0);
  f.left = Image(10, 10);
  EXPECT_THROW(writer.write(f), ParamError);
  f = frame("../escape", 0);
  EXPECT_THROW(writer.write(f), ParamError);
  f = frame("", 0);
  EXPECT_THROW(writer.write(f), ParamError);
}

TEST(Dataset, RecoversRingsWhenTheSweepHasNone) {
  test::TempDir dir;
  const DatasetWriter writer(dir.file("data"), cameras(), Target{});
  Frame f = frame("000000", 0);
  const std::vector<std::uint16_t> truth = f.lidar.ring;
  f.lidar.ring.clear();
  writer.write(f);
  const Frame read = Dataset::open(dir.file("data")).load(0);
  EXPECT_TRUE(read.rings_recovered());
  EXPECT_EQ(read.ring_source, RingSource::LaserModel);
  ASSERT_TRUE(read.ring_recovery.has_value());
  EXPECT_EQ(read.ring_recovery->rings, 16);
  ASSERT_EQ(read.lidar.ring.size(), truth.size());
  for (std::size_t i = 0; i < truth.size(); ++i) {
    if (read.lidar.points[i].allFinite()) {
      EXPECT_EQ(read.lidar.ring[i], truth[i]) << i;
    }
  }
}

TEST(Dataset, TargetAndGroundTruthAreOptional) {
  test::TempDir dir;
  const std::string folder = write_dataset(dir);
  fs::remove(folder + "/target.yaml");
  fs::remove(folder + "/ground_truth.yaml");
  const Dataset dataset = Dataset::open(folder);
  EXPECT_FALSE(dataset.has_target_file());
  EXPECT_EQ(dataset.target().board_width, Target{}.board_width);
  EXPECT_FALSE(dataset.ground_truth().has_value());
}

TEST(Dataset, IgnoresFilesThatAreNotFrames) {
  test::TempDir dir;
  const std::string folder = write_dataset(dir);
  test::write_text(folder + "/lidar/README.txt", "notes");
  test::write_text(folder + "/left/.hidden.png", "x");
  test::write_text(folder + "/right/000001.png.tmp.12.0", "x");
  fs::create_directories(folder + "/lidar/000009.pcd");  // a folder, not a file
  EXPECT_EQ(Dataset::open(folder).size(), 3u);
}

TEST(Dataset, MissingPartsAreFileErrorsNamingThem) {
  test::TempDir dir;
  EXPECT_FILE_ERROR(Dataset::open(dir.file("nowhere")), dir.file("nowhere"), "no such");
  const std::string folder = write_dataset(dir);
  fs::rename(folder + "/left.yaml", folder + "/left.yaml.bak");
  EXPECT_FILE_ERROR(Dataset::open(folder), folder + "/left.yaml", "missing file");
  fs::rename(folder + "/left.yaml.bak", folder + "/left.yaml");

  test::write_text(folder + "/right.yaml", "image_width: 64\nimage_height: [48\n");
  EXPECT_FILE_ERROR(Dataset::open(folder), folder + "/right.yaml", "malformed YAML");
  write_camera_info(folder + "/right.yaml", cameras().right);

  test::write_text(folder + "/target.yaml", "board_width: -1\n");
  EXPECT_FILE_ERROR(Dataset::open(folder), folder + "/target.yaml", "board_width");
  write_target(folder + "/target.yaml", Target{});

  test::write_text(folder + "/ground_truth.yaml", "T_lidar_camera: 1\n");
  EXPECT_FILE_ERROR(Dataset::open(folder).ground_truth(), folder + "/ground_truth.yaml");

  fs::rename(folder + "/right", folder + "/right.bak");
  EXPECT_FILE_ERROR(Dataset::open(folder), folder + "/right", "missing folder");
}

TEST(Dataset, StemsThatDifferBetweenFoldersAreListed) {
  test::TempDir dir;
  const std::string folder = write_dataset(dir);
  fs::remove(folder + "/right/000001.png");
  fs::copy_file(folder + "/left/000000.png", folder + "/left/000009.png");
  EXPECT_FILE_ERROR(Dataset::open(folder), folder,
                    "000001 (no right/000001.png), 000009 (no lidar/000009.pcd right/000009.png)");
  for (int i = 10; i < 20; ++i)
    fs::copy_file(folder + "/lidar/000000.pcd",
                  folder + "/lidar/0000" + std::to_string(i) + ".pcd");
  EXPECT_FILE_ERROR(Dataset::open(folder), folder, "and 7 more");
}

TEST(Dataset, EmptyFolderHasNoFrames) {
  test::TempDir dir;
  const DatasetWriter writer(dir.file("data"), cameras(), Target{});
  EXPECT_FILE_ERROR(Dataset::open(dir.file("data")), dir.file("data"), "no frames");
}

TEST(Dataset, BrokenFrameFilesAreFileErrorsNamingThem) {
  test::TempDir dir;
  const std::string folder = write_dataset(dir);
  const Dataset dataset = Dataset::open(folder);

  write_png(dataset.left_path("000000"), Image(10, 12));
  EXPECT_FILE_ERROR(dataset.load(0), dataset.left_path("000000"),
                    "image is 10x12 but left.yaml says 64x48");
  write_png(dataset.right_path("000001"), Image(kWidth + 1, kHeight, 3));
  EXPECT_FILE_ERROR(dataset.load(1), dataset.right_path("000001"), "65x48");
  test::write_text(dataset.left_path("000001"), "not a png at all");
  EXPECT_FILE_ERROR(dataset.load(1), dataset.left_path("000001"), "cannot decode");
  test::write_text(dataset.lidar_path("000002"),
                   "VERSION 0.7\nFIELDS x y\nSIZE 4 4\nWIDTH 1\nDATA ascii\n1 2\n");
  EXPECT_FILE_ERROR(dataset.load(2), dataset.lidar_path("000002"), "no field z");
  test::write_text(dataset.lidar_path("000002"), std::string(100, '\x01'));
  EXPECT_FILE_ERROR(dataset.load(2), dataset.lidar_path("000002"));
}

StereoCamera raw_cameras() {
  StereoCamera raw = cameras();
  raw.images = ImageKind::Raw;
  for (CameraInfo* camera : {&raw.left, &raw.right}) {
    camera->distortion_coefficients = {-0.2, 0.05, 0.001, -0.001, 0.0};
    camera->camera_matrix(0, 2) = 32.5;  // K is the raw camera's, not P's
  }
  return raw;
}

TEST(DatasetWriter, RawCamerasGetADatasetYaml) {
  test::TempDir dir;
  const DatasetWriter writer(dir.file("raw"), raw_cameras(), Target{});
  writer.write(frame("000000", 0));
  EXPECT_EQ(read_dataset_info(dir.file("raw/dataset.yaml")).images, ImageKind::Raw);
  const Dataset dataset = Dataset::open(dir.file("raw"));
  EXPECT_EQ(dataset.cameras().images, ImageKind::Raw);
  EXPECT_TRUE(dataset.has_dataset_file());
  EXPECT_TRUE(dataset.warnings().empty());
  EXPECT_EQ(dataset.cameras().left.distortion_coefficients,
            raw_cameras().left.distortion_coefficients);

  // A rectified dataset written into the same folder does not keep it.
  const DatasetWriter rectified(dir.file("raw"), cameras(), Target{});
  EXPECT_FALSE(fs::exists(dir.file("raw/dataset.yaml")));
  EXPECT_EQ(Dataset::open(dir.file("raw")).cameras().images, ImageKind::Rectified);
}

TEST(DatasetWriter, RefusesARawPairThatCannotBeRectified) {
  test::TempDir dir;
  StereoCamera raw = raw_cameras();
  raw.left.distortion_model = "rational_polynomial";
  EXPECT_FILE_ERROR(DatasetWriter(dir.file("a"), raw, Target{}), dir.file("a/left.yaml"),
                    "distortion_model 'rational_polynomial'");
}

TEST(Dataset, WarnsWhenRectifiedImagesComeWithDistortion) {
  test::TempDir dir;
  const std::string folder = write_dataset(dir);
  EXPECT_TRUE(Dataset::open(folder).warnings().empty());
  CameraInfo left = cameras().left;
  left.distortion_coefficients = {-0.2, 0.05, 0.0, 0.0, 0.0};
  write_camera_info(folder + "/left.yaml", left);
  CameraInfo right = cameras().right;
  right.rectification_matrix = Eigen::AngleAxisd(0.01, Eigen::Vector3d::UnitY()).toRotationMatrix();
  write_camera_info(folder + "/right.yaml", right);
  const Dataset dataset = Dataset::open(folder);
  ASSERT_EQ(dataset.warnings().size(), 2u);
  EXPECT_NE(dataset.warnings()[0].find(folder + "/left.yaml: distortion_coefficients are not zero"),
            std::string::npos)
      << dataset.warnings()[0];
  EXPECT_NE(dataset.warnings()[0].find("images: raw"), std::string::npos);
  EXPECT_NE(dataset.warnings()[1].find(folder + "/right.yaml: rectification_matrix is not the identity"),
            std::string::npos)
      << dataset.warnings()[1];
  // Declared raw, the same folder is what it says: no warning.
  test::write_text(folder + "/dataset.yaml", "images: raw\n");
  EXPECT_TRUE(Dataset::open(folder).warnings().empty());
}

TEST(Dataset, DatasetYamlErrorsNameTheFile) {
  test::TempDir dir;
  const std::string folder = write_dataset(dir);
  test::write_text(folder + "/dataset.yaml", "images: raww\n");
  EXPECT_FILE_ERROR(Dataset::open(folder), folder + "/dataset.yaml", "images: 'raww'");
  test::write_text(folder + "/dataset.yaml", "imagse: raw\n");
  EXPECT_FILE_ERROR(Dataset::open(folder), folder + "/dataset.yaml", "unknown key 'imagse'");
  // Raw images need a pair that can be rectified: this one has 3 coefficients.
  test::write_text(folder + "/dataset.yaml", "images: raw\n");
  CameraInfo left = cameras().left;
  left.distortion_coefficients = {-0.2, 0.05, 0.0};
  write_camera_info(folder + "/left.yaml", left);
  EXPECT_FILE_ERROR(Dataset::open(folder), folder + "/left.yaml", "3 distortion_coefficients");
}

// `lidar: accumulated` (DATASET.md v3): the image frames are the frames;
// each lidar file pairs with those from its stem up to the next one's.
TEST(Dataset, AnAccumulatedCloudPairsWithTheImageFramesItCovers) {
  test::TempDir dir;
  const std::string folder = write_dataset(dir);
  for (const char* stem : {"000003", "000004", "000005"}) {
    fs::copy_file(folder + "/left/000000.png", folder + "/left/" + stem + ".png");
    fs::copy_file(folder + "/right/000000.png", folder + "/right/" + stem + ".png");
  }
  fs::remove(folder + "/lidar/000000.pcd");
  fs::rename(folder + "/lidar/000002.pcd", folder + "/lidar/000004.pcd");
  test::write_text(folder + "/dataset.yaml", "lidar: accumulated\n");
  const Dataset dataset = Dataset::open(folder);
  EXPECT_TRUE(dataset.accumulated());
  ASSERT_EQ(dataset.size(), 6u);
  EXPECT_EQ(dataset.lidar_stems(), (std::vector<std::string>{"000001", "000004"}));
  const std::vector<std::string> covering{"", "000001", "000001", "000001", "000004", "000004"};
  for (std::size_t i = 0; i < dataset.size(); ++i) EXPECT_EQ(dataset.lidar_stem(i), covering[i]) << i;

  const Frame before = dataset.load(0);  // before the first lidar file: images, no lidar
  EXPECT_TRUE(before.lidar_stem.empty());
  EXPECT_TRUE(before.lidar.empty());
  EXPECT_FALSE(before.left.empty());
  const Frame covered = dataset.load(3);
  EXPECT_EQ(covered.stem, "000003");
  EXPECT_EQ(covered.lidar.size(), frame("000001", 1).lidar.size());
  const Frame images = dataset.load_images(5);
  EXPECT_EQ(images.lidar_stem, "000004");
  EXPECT_TRUE(images.lidar.empty());
  EXPECT_FALSE(images.right.empty());

  // A lidar file with no image frame of its stem is named.
  fs::copy_file(folder + "/lidar/000001.pcd", folder + "/lidar/000007.pcd");
  EXPECT_FILE_ERROR(Dataset::open(folder), folder + "/lidar/000007.pcd", "no image frame 000007");
  fs::remove(folder + "/lidar/000007.pcd");
  fs::remove(folder + "/right/000005.png");
  EXPECT_FILE_ERROR(Dataset::open(folder), folder, "000005 (no right/000005.png)");
}

TEST(Dataset, AMisspeltLidarFormIsNamed) {
  test::TempDir dir;
  const std::string folder = write_dataset(dir);
  test::write_text(folder + "/dataset.yaml", "lidar: acumulated\n");
  EXPECT_FILE_ERROR(Dataset::open(folder), folder + "/dataset.yaml",
                    "lidar: 'acumulated' is neither sweeps nor accumulated");
  test::write_text(folder + "/dataset.yaml", "lidar_form: accumulated\n");
  EXPECT_FILE_ERROR(Dataset::open(folder), folder + "/dataset.yaml", "unknown key 'lidar_form' (known: images, lidar)");
}

// An organised sweep without a ring field: its rows are its rings.
TEST(Dataset, TakesRingsFromTheRowsOfAnOrganisedSweep) {
  test::TempDir dir;
  const std::string folder = write_dataset(dir);
  test::OrganisedSweep sweep = test::corridor_sweep(test::vlp16_table(), {});
  write_pcd(folder + "/lidar/000001.pcd", sweep.cloud, PcdEncoding::Binary, sweep.rows);
  const Frame read = Dataset::open(folder).load(1);
  EXPECT_EQ(read.ring_source, RingSource::OrganisedRows);
  ASSERT_TRUE(read.ring_recovery.has_value());
  EXPECT_EQ(read.ring_recovery->rings, 16);
  for (std::size_t i = 0; i < read.lidar.size(); ++i) {
    if (read.lidar.points[i].allFinite()) {
      ASSERT_EQ(read.lidar.ring[i], i / sweep.columns) << i;
    }
  }
}

}  // namespace
}  // namespace l2s::io

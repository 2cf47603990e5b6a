// target.yaml markers (DATASET.md v2): the default marker board, a round
// trip, old files without markers, and bad marker fields named in the error.
#include <l2s/error.hpp>
#include <l2s/io/target_yaml.hpp>
#include <l2s/target.hpp>

#include "support/test_data.hpp"

#include <gtest/gtest.h>

namespace l2s {
namespace {

TEST(MarkerLayout, DefaultMarkerBoardIsTheDatasetMdOne) {
  const Target target = Target::preset("markers");
  ASSERT_TRUE(target.markers);
  EXPECT_EQ(target.markers->dictionary, "DICT_6X6_250");
  EXPECT_EQ(target.markers->size, 0.2);
  EXPECT_EQ(target.markers->ids, (std::vector<int>{1, 2, 3, 4}));
  EXPECT_EQ(target.markers->centres[1], Eigen::Vector2d(0.55, 0.35));
  EXPECT_NO_THROW(target.validate());
  EXPECT_FALSE(Target{}.markers);  // the plain default board has none
}

TEST(MarkerLayout, CornersStartTopLeftAndGoClockwiseAsSeenFromTheFront) {
  const auto corners = MarkerLayout::corners_default().corners(0);  // centre (-0.55, 0.35)
  EXPECT_TRUE(corners[0].isApprox(Eigen::Vector3d(-0.65, 0.45, 0.0)));
  EXPECT_TRUE(corners[1].isApprox(Eigen::Vector3d(-0.45, 0.45, 0.0)));
  EXPECT_TRUE(corners[2].isApprox(Eigen::Vector3d(-0.45, 0.25, 0.0)));
  EXPECT_TRUE(corners[3].isApprox(Eigen::Vector3d(-0.65, 0.25, 0.0)));
}

TEST(TargetYaml, MarkersRoundTripAndOldFilesStillRead) {
  test::TempDir dir;
  Target target = Target::with_default_markers();
  target.markers->dictionary = "DICT_4X4_50";
  target.markers->ids = {7, 0};
  target.markers->centres = {Eigen::Vector2d(0.0, 0.38), Eigen::Vector2d(-0.6, -0.4)};
  target.markers->size = 0.1;
  io::write_target(dir.file("target.yaml"), target);
  const Target back = io::read_target(dir.file("target.yaml"));
  ASSERT_TRUE(back.markers);
  EXPECT_EQ(back.markers->dictionary, "DICT_4X4_50");
  EXPECT_EQ(back.markers->ids, target.markers->ids);
  EXPECT_EQ(back.markers->centres, target.markers->centres);
  EXPECT_EQ(back.markers->size, 0.1);

  test::write_text(dir.file("old.yaml"), "board_width: 1.4\nhole_radius: 0.12\n");
  EXPECT_FALSE(io::read_target(dir.file("old.yaml")).markers);
}

TEST(TargetYaml, DatasetMdMarkersExampleReads) {
  test::TempDir dir;
  test::write_text(dir.file("target.yaml"),
                   "markers:\n  dictionary: DICT_6X6_250\n  size: 0.20\n  ids: [1, 2, 3, 4]\n"
                   "  centres: [[-0.55, 0.35], [0.55, 0.35], [-0.55, -0.35], [0.55, -0.35]]\n");
  const Target target = io::read_target(dir.file("target.yaml"));
  ASSERT_TRUE(target.markers);
  EXPECT_EQ(target.markers->centres, MarkerLayout::corners_default().centres);
}

struct BadMarkers {
  const char* name;
  const char* yaml;
  const char* field;  // the error names it
};

class TargetYamlBadMarkers : public ::testing::TestWithParam<BadMarkers> {};

TEST_P(TargetYamlBadMarkers, FileErrorNamesTheField) {
  test::TempDir dir;
  const std::string path = dir.file("target.yaml");
  test::write_text(path, std::string("markers:\n") + GetParam().yaml);
  try {
    io::read_target(path);
    FAIL() << "no error for " << GetParam().yaml;
  } catch (const FileError& e) {
    EXPECT_EQ(e.path(), path);
    EXPECT_NE(std::string(e.what()).find(GetParam().field), std::string::npos) << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(
    Fields, TargetYamlBadMarkers,
    ::testing::Values(
        BadMarkers{"UnknownDictionary", "  dictionary: DICT_9X9_1\n  ids: [1]\n  centres: [[-0.55, 0.35]]\n",
                   "markers.dictionary"},
        BadMarkers{"NegativeSize", "  size: -0.2\n  ids: [1]\n  centres: [[-0.55, 0.35]]\n", "markers.size"},
        BadMarkers{"SizeNotANumber", "  size: big\n  ids: [1]\n  centres: [[-0.55, 0.35]]\n", "markers.size"},
        BadMarkers{"IdPastTheDictionary", "  ids: [250]\n  centres: [[-0.55, 0.35]]\n", "markers.ids"},
        BadMarkers{"DuplicateIds", "  ids: [1, 1]\n  centres: [[-0.55, 0.35], [0.55, 0.35]]\n", "markers.ids"},
        BadMarkers{"IdsMissing", "  centres: [[-0.55, 0.35]]\n", "markers.ids"},
        BadMarkers{"FewerCentresThanIds", "  ids: [1, 2]\n  centres: [[-0.55, 0.35]]\n", "markers.centres"},
        BadMarkers{"CentreNotAPair", "  ids: [1]\n  centres: [[-0.55]]\n", "markers.centres"},
        BadMarkers{"OffTheBoard", "  ids: [1]\n  centres: [[-0.65, 0.35]]\n", "markers.centres"},
        BadMarkers{"OverAHole", "  ids: [1]\n  centres: [[-0.25, 0.2]]\n", "markers.centres"},
        BadMarkers{"Overlapping", "  ids: [1, 2]\n  centres: [[-0.55, 0.35], [-0.45, 0.35]]\n", "markers.centres"},
        BadMarkers{"NotAMap", "  [1, 2]\n", "markers"}),
    [](const auto& info) { return std::string(info.param.name); });

TEST(Target, MarkerErrorsNameTheField) {
  Target target = Target::with_default_markers();
  target.markers->size = 0.0;
  try {
    target.validate();
    FAIL();
  } catch (const ParamError& e) {
    EXPECT_EQ(e.field(), "markers.size");
  }
}

}  // namespace
}  // namespace l2s

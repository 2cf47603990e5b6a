#include <l2s/error.hpp>
#include <l2s/target.hpp>

#include <gtest/gtest.h>

namespace {

TEST(Target, DefaultsMatchTheDatasetContract) {
  const l2s::Target target;
  EXPECT_DOUBLE_EQ(target.board_width, 1.4);
  EXPECT_DOUBLE_EQ(target.board_height, 1.0);
  EXPECT_DOUBLE_EQ(target.hole_spacing_x, 0.5);
  EXPECT_NO_THROW(target.validate());
}

TEST(Target, HoleCentresAreLabelledFromTheFront) {
  const auto centers = l2s::Target{}.hole_centers();
  const auto& top_left = centers[static_cast<int>(l2s::Hole::TopLeft)];
  const auto& bottom_right = centers[static_cast<int>(l2s::Hole::BottomRight)];
  EXPECT_DOUBLE_EQ(top_left.x(), -0.25);
  EXPECT_DOUBLE_EQ(top_left.y(), 0.2);
  EXPECT_DOUBLE_EQ(bottom_right.x(), 0.25);
  EXPECT_DOUBLE_EQ(bottom_right.y(), -0.2);
}

TEST(Target, Paper2017PresetIsTheSmallerBoard) {
  const auto target = l2s::Target::preset("paper2017");
  EXPECT_DOUBLE_EQ(target.board_width, 1.2);
  EXPECT_DOUBLE_EQ(target.board_height, 0.8);
  EXPECT_DOUBLE_EQ(target.hole_spacing_x, 0.3);
  EXPECT_DOUBLE_EQ(target.hole_spacing_y, 0.3);
  EXPECT_NO_THROW(target.validate());
}

TEST(Target, RejectsImpossibleBoardsNamingTheField) {
  l2s::Target overlapping;
  overlapping.hole_spacing_x = 0.2;  // less than the 0.24 m hole diameter
  try {
    overlapping.validate();
    FAIL() << "overlapping holes accepted";
  } catch (const l2s::ParamError& error) {
    EXPECT_EQ(error.field(), "hole_spacing_x");
  }
  l2s::Target too_small;
  too_small.board_height = 0.5;
  EXPECT_THROW(too_small.validate(), l2s::ParamError);
  EXPECT_THROW(l2s::Target::preset("huge"), l2s::ParamError);
}

}  // namespace

// target.yaml: defaults, partial files, round trips and bad input.
#include <l2s/error.hpp>
#include <l2s/io/target_yaml.hpp>

#include "io_test_helpers.hpp"
#include "support/test_data.hpp"

#include <gtest/gtest.h>

namespace l2s::io {
namespace {

void expect_same(const Target& a, const Target& b) {
  EXPECT_EQ(a.board_width, b.board_width);
  EXPECT_EQ(a.board_height, b.board_height);
  EXPECT_EQ(a.board_thickness, b.board_thickness);
  EXPECT_EQ(a.hole_radius, b.hole_radius);
  EXPECT_EQ(a.hole_spacing_x, b.hole_spacing_x);
  EXPECT_EQ(a.hole_spacing_y, b.hole_spacing_y);
}

TEST(TargetYaml, ReadsTheDatasetMdExample) {
  test::TempDir dir;
  test::write_text(
      dir.file("target.yaml"),
      "board_width: 1.2          # outer size\nboard_height: 0.8\nboard_thickness: 0.02\n"
      "hole_radius: 0.12\nhole_spacing_x: 0.3\nhole_spacing_y: 0.3\n");
  expect_same(read_target(dir.file("target.yaml")), Target::paper2017());
}

TEST(TargetYaml, MissingKeysKeepDefaultsAndUnknownKeysAreIgnored) {
  test::TempDir dir;
  test::write_text(dir.file("target.yaml"), "hole_radius: 0.1\nmaterial: plywood\nnotes: [a, b]\n");
  Target expected;
  expected.hole_radius = 0.1;
  expect_same(read_target(dir.file("target.yaml")), expected);
  test::write_text(dir.file("empty.yaml"), "");
  expect_same(read_target(dir.file("empty.yaml")), Target{});
}

TEST(TargetYaml, RoundTripsExactly) {
  test::TempDir dir;
  Target target = Target::paper2017();
  target.board_width = 1.0 / 0.7;
  write_target(dir.file("target.yaml"), target);
  expect_same(read_target(dir.file("target.yaml")), target);
  write_target(dir.file("again.yaml"), target);
  EXPECT_EQ(test::read_bytes(dir.file("target.yaml")), test::read_bytes(dir.file("again.yaml")));
}

TEST(TargetYaml, MissingFileGivesDefaultsOnlyWhenAskedFor) {
  test::TempDir dir;
  expect_same(read_target_or_default(dir.file("target.yaml")), Target{});
  EXPECT_FILE_ERROR(read_target(dir.file("target.yaml")), dir.file("target.yaml"), "missing file");
}

TEST(TargetYaml, BadValuesAreFileErrorsNamingFileAndKey) {
  test::TempDir dir;
  const std::string path = dir.file("target.yaml");
  test::write_text(path, "board_width: wide\n");
  EXPECT_FILE_ERROR(read_target(path), path, "board_width");
  test::write_text(path, "hole_radius: [0.1]\n");
  EXPECT_FILE_ERROR(read_target(path), path, "hole_radius");
  test::write_text(path, "board_width: 1.4\n  bad indent: [\n");
  EXPECT_FILE_ERROR(read_target(path), path, "malformed YAML");
  test::write_text(path, "- 1.4\n");
  EXPECT_FILE_ERROR(read_target(path), path, "map");
  // Parses fine but the holes overlap: Target::validate's message, naming the file.
  test::write_text(path, "hole_radius: 0.3\n");
  EXPECT_FILE_ERROR(read_target(path), path, "hole_spacing_x");
  EXPECT_FILE_ERROR(read_target_or_default(path), path, "hole_spacing_x");
}

}  // namespace
}  // namespace l2s::io

// The camera side of scene files: every rig and look key is read, what the
// scene record writes reads back to the same rig and look, and bad input
// names its key.

#include <l2s/sim/scene_yaml.hpp>

#include <l2s/error.hpp>

#include "sim/scene_yaml_camera.hpp"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <string>

namespace l2s::sim {
namespace {

TEST(SceneYamlCamera, ReadsTheRigAndTheLook) {
  const SimulationConfig c = parse_simulation_config(R"(
camera:
  width: 1280
  height: 960
  horizontal_fov: 1.152
  baseline: 0.12
  distortion: equidistant
  right_rotation: [0.001, 0.002, 0.003]
  left: {aspect: 1.003, principal_offset: [5.0, -3.0]}
  right:
    distortion: {model: plumb_bob, coefficients: [-0.1, 0.03, 0.0001, 0.0002, 0.0]}
appearance:
  board_texture: low-contrast
  background: tiles
  sky: daylight
  brick_length: 0.15
  joint_width: 0.004
  to_light: [-2.0, 0.0, 2.0]
  shadows: true
  ambient: 0.25
  exposure: 1.3
  vignetting: 0.2
  blur_sigma: 0.8
  gamma: 2.2
  colour: true
)");
  const StereoRig& rig = c.rig;
  EXPECT_EQ(rig.images(), ImageKind::Raw);
  EXPECT_EQ(rig.lenses[0].distortion.model, DistortionModel::Equidistant);  // from `distortion: equidistant`
  EXPECT_DOUBLE_EQ(rig.lenses[0].aspect, 1.003);
  EXPECT_DOUBLE_EQ(rig.lenses[0].principal_offset.y(), -3.0);
  EXPECT_EQ(rig.lenses[1].distortion.model, DistortionModel::PlumbBob);
  EXPECT_DOUBLE_EQ(rig.lenses[1].distortion.coefficients[3], 0.0002);
  EXPECT_DOUBLE_EQ(rig.right_rotation.z(), 0.003);
  EXPECT_NE(rig.right_offset.norm(), 0.0) << "the typical pair's mount stays where not overridden";
  const Appearance& a = c.appearance;
  EXPECT_EQ(a.board, BoardTexture::LowContrast);
  EXPECT_EQ(a.background, Background::Tiles);
  EXPECT_EQ(a.sky, Sky::Daylight);
  EXPECT_DOUBLE_EQ(a.brick_length, 0.15);
  EXPECT_NEAR(a.to_light.x(), -std::sqrt(0.5), 1e-12);
  EXPECT_TRUE(a.shadows && a.colour);
  EXPECT_DOUBLE_EQ(a.gamma, 2.2);
  EXPECT_DOUBLE_EQ(a.blur_sigma, 0.8);
}

TEST(SceneYamlCamera, WhatTheRecordWritesReadsBack) {
  StereoRig rig;
  rig.width = 1920;
  rig.height = 1200;
  rig.horizontal_fov = 1.5;
  rig = rig.with_real_lenses(DistortionModel::PlumbBob);
  rig.raw_images = true;
  rig.roll = 1.5707963267948966;  // on its side
  Appearance look;
  look.board = BoardTexture::WoodGrain;
  look.background = Background::Bricks;
  look.shadows = true;
  look.to_light = Eigen::Vector3d(-0.5, 0.5, 0.7).normalized();
  YAML::Emitter out;
  out.SetDoublePrecision(17);
  out << YAML::BeginMap;
  detail::emit_camera_block(out, rig);
  detail::emit_appearance_block(out, look);
  out << YAML::EndMap;
  const SimulationConfig c = parse_simulation_config(out.c_str());
  EXPECT_EQ(c.rig.width, 1920);
  EXPECT_EQ(c.rig.raw_images, true);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(c.rig.lenses[i].distortion.coefficients, rig.lenses[i].distortion.coefficients);
    EXPECT_EQ(c.rig.lenses[i].principal_offset, rig.lenses[i].principal_offset);
    EXPECT_EQ(c.rig.lenses[i].focal_scale, rig.lenses[i].focal_scale);
  }
  EXPECT_EQ(c.rig.right_rotation, rig.right_rotation);
  EXPECT_EQ(c.rig.roll, rig.roll);
  EXPECT_EQ(c.appearance.board, BoardTexture::WoodGrain);
  EXPECT_EQ(c.appearance.background, Background::Bricks);
  EXPECT_TRUE(c.appearance.shadows);
  EXPECT_TRUE(c.appearance.to_light.isApprox(look.to_light, 1e-15));
}

TEST(SceneYamlCamera, BadInputNamesTheKey) {
  const auto message = [](const std::string& text) {
    try {
      parse_simulation_config(text, "scene.yaml");
    } catch (const FileError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("camera: {distortion: fisheye}").find("camera.distortion"), std::string::npos);
  EXPECT_NE(message("camera: {left: {aspect: wide}}").find("camera.left.aspect"), std::string::npos);
  EXPECT_NE(message("camera: {left: {aspect: 1.3}}").find("camera.left.aspect"), std::string::npos);
  EXPECT_NE(message("camera: {right: {distortion: {model: equidistant, coefficients: [0.1]}}}")
                .find("camera.right.distortion.coefficients"),
            std::string::npos);
  EXPECT_NE(message("camera: {right_offset: [0, 0]}").find("camera.right_offset"), std::string::npos);
  EXPECT_NE(message("camera: {roll: .nan}").find("camera.roll"), std::string::npos);
  EXPECT_NE(message("appearance: {background: brick}").find("appearance.background"), std::string::npos);
  EXPECT_NE(message("appearance: {shadow: true}").find("appearance.shadow"), std::string::npos);
  EXPECT_NE(message("appearance: {blur_sigma: 9}").find("appearance.blur_sigma"), std::string::npos);
}

}  // namespace
}  // namespace l2s::sim

#pragma once
// RANSAC for a plane parallel to a given axis (private; see vertical_plane_ransac.cpp).

#include <l2s/geometry.hpp>

#include <Eigen/Core>
#include <cstdint>
#include <random>
#include <vector>

namespace l2s::detail {

struct VerticalPlaneRansacParams {
  double distance_threshold = 0.01;  // [m]
  double max_sin_axis = 0.52;        // sin(max_angle): |normal . axis| must not exceed it
  double min_cos_axis = 0.0;         // |normal . axis| must reach it (> 0: a level plane, not a vertical one)
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  int max_iterations = 1000;
  double sample_radius = 0.5;  // [m]
  const std::vector<double>* tolerance = nullptr;  // per-sample consensus distance [m], overrides distance_threshold
};

struct VerticalPlaneRansacResult {
  bool found = false;
  Plane plane;
  std::size_t consensus = 0;  // sample points within distance_threshold
};

/// `samples` must be in random order: hypotheses are pre-scored on a prefix.
VerticalPlaneRansacResult find_vertical_plane(const std::vector<Eigen::Vector3d>& samples,
                                              const VerticalPlaneRansacParams& params,
                                              std::mt19937_64& rng);

}  // namespace l2s::detail

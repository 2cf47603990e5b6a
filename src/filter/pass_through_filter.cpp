#include <l2s/pass_through_filter.hpp>

#include <l2s/error.hpp>

#include <cmath>

namespace l2s {

void PassThroughFilter::Params::validate() const {
  static const char* const kAxis[3] = {"x", "y", "z"};
  for (int i = 0; i < 3; ++i) {
    if (std::isnan(min_xyz[i])) throw ParamError(std::string("min_xyz.") + kAxis[i], "is NaN");
    if (std::isnan(max_xyz[i])) throw ParamError(std::string("max_xyz.") + kAxis[i], "is NaN");
    if (!(max_xyz[i] >= min_xyz[i]))
      throw ParamError(std::string("max_xyz.") + kAxis[i], "must be >= min_xyz." + std::string(kAxis[i]));
  }
  if (!(min_range >= 0.0) || !std::isfinite(min_range))
    throw ParamError("min_range", "must be a finite distance >= 0");
  if (!(max_range > min_range)) throw ParamError("max_range", "must be > min_range");
}

PassThroughFilter::PassThroughFilter() : PassThroughFilter(Params{}) {}

PassThroughFilter::PassThroughFilter(Params params) : params_(std::move(params)) {
  params_.validate();
}

PassThroughFilter::Result PassThroughFilter::filter(const std::vector<Eigen::Vector3d>& points) const {
  Result result;
  result.kept.reserve(points.size());
  // Compare squared ranges: no sqrt per point on million-point stereo clouds.
  const double min_r2 = params_.min_range * params_.min_range;
  const double max_r2 = params_.max_range * params_.max_range;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d& p = points[i];
    if (!p.allFinite()) {
      ++result.dropped_non_finite;
    } else if ((p.array() < params_.min_xyz.array()).any() ||
               (p.array() > params_.max_xyz.array()).any()) {
      ++result.dropped_box;
    } else {
      const double r2 = p.squaredNorm();
      if (r2 < min_r2 || r2 > max_r2)
        ++result.dropped_range;
      else
        result.kept.push_back(i);
    }
  }
  return result;
}

LidarCloud select(const LidarCloud& cloud, const std::vector<std::size_t>& indices) {
  LidarCloud out;
  out.points.reserve(indices.size());
  if (cloud.has_ring()) out.ring.reserve(indices.size());
  if (cloud.has_intensity()) out.intensity.reserve(indices.size());
  for (std::size_t i : indices) {
    out.points.push_back(cloud.points.at(i));
    if (cloud.has_ring()) out.ring.push_back(cloud.ring.at(i));
    if (cloud.has_intensity()) out.intensity.push_back(cloud.intensity.at(i));
  }
  return out;
}

}  // namespace l2s

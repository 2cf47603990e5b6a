// The plumb_bob and equidistant lens models (OpenCV calib3d "Detailed
// description" and cv::fisheye's model documentation) and their inverses.
// The inverse is Newton's method on the model itself, so it agrees with the
// forward model to the iteration tolerance, not to a fixed iteration count.

#include <l2s/sim/lens.hpp>

#include <l2s/error.hpp>

#include <Eigen/LU>
#include <algorithm>
#include <cmath>

namespace l2s::sim {
namespace {

constexpr double kTolerance = 1e-13;  // normalised units: ~1e-10 px at fx = 1000
constexpr int kMaxIterations = 40;

/// theta (1 + k1 theta^2 + ... + k4 theta^8) and its derivative.
void equidistant_profile(const std::array<double, 5>& k, double theta, double* value,
                         double* slope) {
  const double t2 = theta * theta;
  const double poly = 1.0 + t2 * (k[0] + t2 * (k[1] + t2 * (k[2] + t2 * k[3])));
  *value = theta * poly;
  *slope = 1.0 + t2 * (3.0 * k[0] + t2 * (5.0 * k[1] + t2 * (7.0 * k[2] + t2 * 9.0 * k[3])));
}

Eigen::Vector2d plumb_bob(const std::array<double, 5>& c, const Eigen::Vector2d& p,
                          Eigen::Matrix2d* jacobian) {
  const double k1 = c[0], k2 = c[1], p1 = c[2], p2 = c[3], k3 = c[4];
  const double x = p.x(), y = p.y();
  const double r2 = x * x + y * y;
  const double radial = 1.0 + r2 * (k1 + r2 * (k2 + r2 * k3));
  if (jacobian) {
    // d(radial)/dx = dr * x, d(radial)/dy = dr * y.
    const double dr = 2.0 * k1 + r2 * (4.0 * k2 + r2 * 6.0 * k3);
    (*jacobian)(0, 0) = radial + dr * x * x + 2.0 * p1 * y + 6.0 * p2 * x;
    (*jacobian)(0, 1) = dr * x * y + 2.0 * p1 * x + 2.0 * p2 * y;
    (*jacobian)(1, 0) = dr * x * y + 2.0 * p1 * x + 2.0 * p2 * y;
    (*jacobian)(1, 1) = radial + dr * y * y + 6.0 * p1 * y + 2.0 * p2 * x;
  }
  return {x * radial + 2.0 * p1 * x * y + p2 * (r2 + 2.0 * x * x),
          y * radial + p1 * (r2 + 2.0 * y * y) + 2.0 * p2 * x * y};
}

Eigen::Vector2d undistort_plumb_bob(const std::array<double, 5>& c, const Eigen::Vector2d& target,
                                    Eigen::Vector2d p) {
  Eigen::Matrix2d J;
  Eigen::Vector2d residual = plumb_bob(c, p, &J) - target;
  for (int i = 0; i < kMaxIterations && residual.lpNorm<Eigen::Infinity>() > kTolerance; ++i) {
    const double det = J.determinant();
    if (!(std::abs(det) > 1e-12)) break;  // at a fold: no inverse here
    Eigen::Vector2d step = J.inverse() * residual;
    // Halve the step while it makes things worse: keeps Newton inside the
    // basin near strong distortion without changing its fast final convergence.
    for (int halvings = 0; halvings < 20; ++halvings) {
      Eigen::Matrix2d J_next;
      const Eigen::Vector2d next = plumb_bob(c, p - step, &J_next) - target;
      if (next.squaredNorm() < residual.squaredNorm() || halvings == 19) {
        p -= step;
        residual = next;
        J = J_next;
        break;
      }
      step *= 0.5;
    }
  }
  return p;
}

Eigen::Vector2d undistort_equidistant(const std::array<double, 5>& k, const Eigen::Vector2d& target,
                                      const Eigen::Vector2d& guess) {
  const double rd = target.norm();
  if (rd < 1e-15) return target;
  double theta = std::atan(guess.norm());
  for (int i = 0; i < kMaxIterations; ++i) {
    double value = 0.0, slope = 0.0;
    equidistant_profile(k, theta, &value, &slope);
    if (!(slope > 1e-12)) break;
    const double step = (value - rd) / slope;
    theta = std::clamp(theta - step, 0.0, 1.5707963267948);
    if (std::abs(step) < kTolerance) break;
  }
  return target * (std::tan(theta) / rd);
}

}  // namespace

DistortionModel distortion_model_from_name(const std::string& name, const std::string& field) {
  if (name == "none") return DistortionModel::None;
  if (name == "plumb_bob") return DistortionModel::PlumbBob;
  if (name == "equidistant") return DistortionModel::Equidistant;
  throw ParamError(field, "unknown distortion model '" + name + "' (none, plumb_bob, equidistant)");
}

const char* name_of(DistortionModel model) {
  switch (model) {
    case DistortionModel::PlumbBob: return "plumb_bob";
    case DistortionModel::Equidistant: return "equidistant";
    case DistortionModel::None: break;
  }
  return "none";
}

bool LensDistortion::distorts() const {
  if (model == DistortionModel::None) return false;
  for (double c : coefficients)
    if (c != 0.0) return true;
  // The equidistant model maps angles, not tangents: even k = 0 distorts.
  return model == DistortionModel::Equidistant;
}

Eigen::Vector2d LensDistortion::distort(const Eigen::Vector2d& p) const {
  switch (model) {
    case DistortionModel::None: return p;
    case DistortionModel::PlumbBob: return plumb_bob(coefficients, p, nullptr);
    case DistortionModel::Equidistant: {
      const double r = p.norm();
      if (r < 1e-15) return p;
      return p * (radial(r) / r);
    }
  }
  return p;
}

Eigen::Vector2d LensDistortion::undistort(const Eigen::Vector2d& distorted) const {
  return undistort(distorted, distorted);
}

Eigen::Vector2d LensDistortion::undistort(const Eigen::Vector2d& distorted,
                                          const Eigen::Vector2d& guess) const {
  switch (model) {
    case DistortionModel::None: return distorted;
    case DistortionModel::PlumbBob: return undistort_plumb_bob(coefficients, distorted, guess);
    case DistortionModel::Equidistant: return undistort_equidistant(coefficients, distorted, guess);
  }
  return distorted;
}

double LensDistortion::radial(double r) const {
  const auto& k = coefficients;
  switch (model) {
    case DistortionModel::None: return r;
    case DistortionModel::PlumbBob: {
      const double r2 = r * r;
      return r * (1.0 + r2 * (k[0] + r2 * (k[1] + r2 * k[4])));
    }
    case DistortionModel::Equidistant: {
      double value = 0.0, slope = 0.0;
      equidistant_profile(k, std::atan(r), &value, &slope);
      return value;
    }
  }
  return r;
}

bool LensDistortion::one_to_one_up_to(double r) const {
  if (model == DistortionModel::None) return true;
  constexpr int kSamples = 64;
  double previous = 0.0;
  for (int i = 1; i <= kSamples; ++i) {
    const double value = radial(r * i / kSamples);
    if (!(value > previous)) return false;
    previous = value;
  }
  return true;
}

std::string LensDistortion::ros_model() const {
  return model == DistortionModel::Equidistant ? "equidistant" : "plumb_bob";
}

std::vector<double> LensDistortion::ros_coefficients() const {
  if (model == DistortionModel::Equidistant)
    return {coefficients[0], coefficients[1], coefficients[2], coefficients[3]};
  if (model == DistortionModel::None) return {0.0, 0.0, 0.0, 0.0, 0.0};
  return {coefficients.begin(), coefficients.end()};
}

void LensDistortion::validate(const std::string& field) const {
  for (double c : coefficients)
    if (!std::isfinite(c)) throw ParamError(field + ".distortion", "coefficients must be finite");
  if (model == DistortionModel::None)
    for (double c : coefficients)
      if (c != 0.0) throw ParamError(field + ".distortion", "model none takes no coefficients");
  if (model == DistortionModel::Equidistant && coefficients[4] != 0.0)
    throw ParamError(field + ".distortion", "equidistant takes four coefficients k1..k4");
  // Beyond these the models describe no lens a calibrator would meet.
  const double radial_limit = model == DistortionModel::Equidistant ? 1.0 : 2.0;
  for (int i : {0, 1, 4})
    if (std::abs(coefficients[i]) > radial_limit)
      throw ParamError(field + ".distortion", "radial coefficients must be within +-" +
                                                  std::to_string(radial_limit));
  const double second_limit = model == DistortionModel::Equidistant ? 1.0 : 0.05;
  for (int i : {2, 3})
    if (std::abs(coefficients[i]) > second_limit)
      throw ParamError(field + ".distortion",
                       model == DistortionModel::Equidistant
                           ? "k3, k4 must be within +-1"
                           : "tangential coefficients p1, p2 must be within +-0.05");
}

LensDistortion typical_distortion(DistortionModel model, double horizontal_fov) {
  const double s = std::clamp((horizontal_fov * 57.29577951308232 - 40.0) / 60.0, 0.0, 1.0);
  LensDistortion d;
  d.model = model;
  if (model == DistortionModel::PlumbBob)
    d.coefficients = {-0.08 - 0.22 * s, 0.02 + 0.08 * s, 4e-4, -3e-4, 0.0};
  else if (model == DistortionModel::Equidistant)
    d.coefficients = {0.02 - 0.04 * s, 0.005, -0.002, 0.0005, 0.0};
  return d;
}

bool CameraLens::ideal() const {
  return focal_scale == 1.0 && aspect == 1.0 && principal_offset.isZero(0.0) &&
         distortion.model == DistortionModel::None;
}

void CameraLens::validate(const std::string& field, int width, int height) const {
  if (!(focal_scale >= 0.8 && focal_scale <= 1.25))
    throw ParamError(field + ".focal_scale", "must be 0.8..1.25");
  if (!(aspect >= 0.95 && aspect <= 1.05)) throw ParamError(field + ".aspect", "must be 0.95..1.05");
  if (!(std::abs(principal_offset.x()) <= 0.1 * width &&
        std::abs(principal_offset.y()) <= 0.1 * height))
    throw ParamError(field + ".principal_offset", "must be within 10 % of the image size");
  distortion.validate(field);
}

}  // namespace l2s::sim

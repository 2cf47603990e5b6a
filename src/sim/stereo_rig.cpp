#include <l2s/sim/stereo_rig.hpp>

#include <l2s/error.hpp>
#include <l2s/sim/settings.hpp>

#include <cmath>

namespace l2s::sim {

double StereoRig::fx() const { return 0.5 * width / std::tan(0.5 * horizontal_fov); }

StereoCamera StereoRig::cameras() const {
  StereoCamera pair;
  pair.left = CameraInfo::ideal("left", width, height, fx(), cx(), cy(), 0.0);
  pair.right = CameraInfo::ideal("right", width, height, fx(), cx(), cy(), baseline);
  return pair;
}

Eigen::Isometry3d StereoRig::T_cambody_optical(int index) const {
  Eigen::Isometry3d T = sim::T_cambody_optical();
  // The right camera sits one baseline along +x_opt, i.e. along -y_body.
  if (index == 1) T.translation() = Eigen::Vector3d(0.0, -baseline, 0.0);
  return T;
}

void StereoRig::validate() const {
  if (width < 16 || width > 16384) throw ParamError("camera.width", "must be 16..16384 px");
  if (height < 16 || height > 16384) throw ParamError("camera.height", "must be 16..16384 px");
  if (!(horizontal_fov > 0.05 && horizontal_fov < 3.0))
    throw ParamError("camera.horizontal_fov", "must be in (0.05, 3.0) rad");
  if (!(baseline > 0.0 && baseline < 5.0)) throw ParamError("camera.baseline", "must be in (0, 5) m");
}

}  // namespace l2s::sim

#pragma once
// Checks of what callers hand the library at run time: the cameras a
// Calibrator is built for and the images given to it and to the camera
// stages. One place, so that every entry point rejects the same inputs with
// the same message, before any work starts.

#include <l2s/camera.hpp>
#include <l2s/types.hpp>

#include <string>

namespace l2s::detail {

/// Throws ParamError naming the field when a rig cannot be calibrated: image
/// sizes not positive, projection matrices not finite, fx or fy not positive,
/// or a stereo baseline -P_right[0][3] / fx_right that is not positive.
void check_cameras(const StereoCamera& cameras);

/// Throws ParamError naming `<name>.<field>` when one camera cannot be used:
/// image size not positive, P not finite, fx or fy not positive.
void check_camera(const CameraInfo& camera, const std::string& name);

/// Throws InputError("<name> image", ...) when `image` is empty, has another
/// channel count than 1 or 3, or pixels that do not fill width x height x channels.
void check_image(const Image& image, const std::string& name);

/// check_image, and the camera's size (when the camera gives one: width > 0).
void check_image(const Image& image, const CameraInfo& camera, const std::string& name);

/// Both images of a pair: check_image, the same size, and the cameras' size
/// (when the cameras give one: width > 0).
void check_stereo_images(const Image& left, const Image& right, const StereoCamera& cameras);

}  // namespace l2s::detail

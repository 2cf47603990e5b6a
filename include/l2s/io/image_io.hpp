#pragma once
// 8-bit images on disk (PNG, and whatever else OpenCV decodes).

#include <l2s/export.hpp>
#include <l2s/types.hpp>

#include <string>

namespace l2s::io {

/// Reads an 8-bit gray or colour image (colour comes back as BGR, 3 channels;
/// an alpha channel is dropped, 16-bit images are scaled to 8 bits: 65535 -> 255).
/// Throws FileError when the file is missing, cannot be decoded, or holds
/// another pixel type (signed or floating point).
L2S_EXPORT Image read_image(const std::string& path);

/// Writes a PNG atomically. Compression 0..9 (zlib level). Throws ParamError
/// when the image is empty, not 1 or 3 channels, or its pixels do not fill it.
L2S_EXPORT void write_png(const std::string& path, const Image& image, int compression = 3);

/// Luminance of an image: the image itself when gray, else BGR -> gray.
L2S_EXPORT Image to_gray(const Image& image);

}  // namespace l2s::io

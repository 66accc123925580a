#pragma once
// Image files through OpenCV's codecs (imgcodecs), loaded the first time an image is read or
// encoded. libopencv_imgcodecs brings 139 shared libraries (GDAL's among them): linked into the
// CLI it cost every start ~95 ms of dynamic linking (a program with the CLI's libraries starts in
// 129 ms with it, 35 ms without), though most runs never touch an image. The codecs sit in a
// module of the project's own, libuwgrasp_imagecodecs.so, looked for in UWGRASP_MODULE_DIR (when
// set), then in ../lib/uwgrasp beside the running program (the build tree's layout), then in the
// installed library directory. PNG files of the plain kinds (png_codec.hpp) are read and written
// through libpng without it.
#include <opencv2/core.hpp>
#include <cstdint>
#include <string>
#include <vector>

namespace uwgrasp::viz {

// The image at `path` as cv::imread reads it with `flags` (cv::IMREAD_*). Throws Error naming
// the file when it is missing, not an image OpenCV reads, or truncated, and when the codecs
// module cannot be loaded.
cv::Mat read_image(const std::string& path, int flags);

// The image encoded in the format of `extension` (".png", ".jpg", ...). Throws Error when
// OpenCV cannot encode it or the module cannot be loaded.
std::vector<std::uint8_t> encode_image(const cv::Mat& image, const std::string& extension);

}  // namespace uwgrasp::viz

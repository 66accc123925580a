#pragma once
// Internal to viz/: PNG files through libpng itself, for the images uwgrasp writes (its pictures,
// the simulator's frames) and the plain ones it reads (grey 8- or 16-bit depth and stereo images,
// 8- or 16-bit colour). OpenCV's codecs (image_files.hpp) bring 139 shared libraries: loading
// them for a --png picture cost a 640 x 480 detection ~45 MB of peak resident set and ~95 ms. Each
// function does what cv::imencode / cv::imread do with the same image, to the byte of the
// pixels, and declines what it does not cover, which is then left to OpenCV.
#include <cstdint>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

namespace uwgrasp::viz::png_detail {

// PNG bytes of an 8- or 16-bit image of 1, 3 or 4 channels (colour in OpenCV's BGR(A) order),
// written with imencode's own settings (sub filter, zlib level 1, run-length strategy). False
// (and `out` empty) for any other image, or when libpng fails.
bool encode(const cv::Mat& image, std::vector<std::uint8_t>& out);

// The image at `path` as cv::imread(path, flags) reads it, for PNG files of grey (8 or 16 bits,
// no transparency) read with IMREAD_UNCHANGED, IMREAD_ANYDEPTH or IMREAD_GRAYSCALE (8 bits),
// and of 8- or 16-bit RGB or RGBA read with IMREAD_UNCHANGED. nullopt for any other file, flag
// or kind of PNG, for a PNG with EXIF data read with a flag that would apply its orientation,
// and for a PNG libpng cannot read (OpenCV then gives the error that names the file).
std::optional<cv::Mat> decode(const std::string& path, int flags);

}  // namespace uwgrasp::viz::png_detail

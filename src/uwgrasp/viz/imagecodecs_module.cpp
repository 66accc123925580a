// The image codecs module (image_files.hpp): OpenCV's imgcodecs behind two C entry points, for
// dlopen. Each returns 0 when done, 1 when OpenCV could not read or encode (or threw).
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

extern "C" {

int uwgrasp_image_read(const char* path, int flags, cv::Mat* out) noexcept {
  try {
    *out = cv::imread(path, flags);
    return out->empty() ? 1 : 0;
  } catch (...) {
    out->release();
    return 1;
  }
}

int uwgrasp_image_encode(const char* extension, const cv::Mat* image, std::vector<unsigned char>* out) noexcept {
  try {
    // An extension no encoder takes is refused here, without OpenCV logging and throwing.
    if (!cv::haveImageWriter(std::string("image") + extension)) return 1;
    return cv::imencode(extension, *image, *out) ? 0 : 1;
  } catch (...) {
    out->clear();
    return 1;
  }
}

}  // extern "C"

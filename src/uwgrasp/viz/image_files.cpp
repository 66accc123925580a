#include "uwgrasp/viz/image_files.hpp"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <optional>
#include <system_error>
#include <utility>

#include "uwgrasp/core/error.hpp"
#include "uwgrasp/viz/png_codec.hpp"

namespace uwgrasp::viz {

namespace {
using ReadFn = int (*)(const char*, int, cv::Mat*) noexcept;
using EncodeFn = int (*)(const char*, const cv::Mat*, std::vector<unsigned char>*) noexcept;

struct Codecs {
  ReadFn read = nullptr;
  EncodeFn encode = nullptr;
};

constexpr const char* kModule = "libuwgrasp_imagecodecs.so";

std::vector<std::filesystem::path> module_dirs() {
  std::vector<std::filesystem::path> dirs;
  if (const char* env = std::getenv("UWGRASP_MODULE_DIR"); env != nullptr && *env != '\0') dirs.emplace_back(env);
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) dirs.push_back(exe.parent_path().parent_path() / "lib" / "uwgrasp");
  dirs.emplace_back(UWGRASP_INSTALLED_MODULE_DIR);
  return dirs;
}

// The module's entry points; the handle stays open for the process's life.
Codecs load() {
  std::string tried;
  for (const std::filesystem::path& dir : module_dirs()) {
    const std::filesystem::path path = dir / kModule;
    tried += (tried.empty() ? "" : ", ") + dir.string();
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) continue;
    void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (handle == nullptr) throw Error(std::string("image codecs: ") + dlerror());
    Codecs c{reinterpret_cast<ReadFn>(dlsym(handle, "uwgrasp_image_read")),
             reinterpret_cast<EncodeFn>(dlsym(handle, "uwgrasp_image_encode"))};
    if (c.read == nullptr || c.encode == nullptr) throw Error("image codecs: " + path.string() + " lacks its entry points");
    return c;
  }
  throw Error(std::string("image codecs: ") + kModule + " not found in " + tried +
              " (set UWGRASP_MODULE_DIR to the folder that holds it)");
}

// Loaded once; a failed load throws and is tried again by the next call.
const Codecs& codecs() {
  static const Codecs c = load();
  return c;
}
}  // namespace

cv::Mat read_image(const std::string& path, int flags) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw Error(path + ": no such file");
  if (std::optional<cv::Mat> png = png_detail::decode(path, flags)) return std::move(*png);
  cv::Mat m;
  if (codecs().read(path.c_str(), flags, &m) != 0 || m.empty())
    throw Error(path + ": cannot read the image (not an image OpenCV reads, or truncated)");
  return m;
}

std::vector<std::uint8_t> encode_image(const cv::Mat& image, const std::string& extension) {
  std::vector<unsigned char> out;
  if (extension == ".png" && png_detail::encode(image, out)) return out;
  if (image.empty() || codecs().encode(extension.c_str(), &image, &out) != 0)
    throw Error("cannot encode a " + extension + " image");
  return out;
}

}  // namespace uwgrasp::viz

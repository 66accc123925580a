#include "uwgrasp/viz/png_codec.hpp"

#include <png.h>
#include <zlib.h>

#include <bit>
#include <csetjmp>
#include <cstdio>
#include <filesystem>
#include <new>
#include <opencv2/imgcodecs.hpp>  // the IMREAD_ flags only
#include <system_error>

namespace uwgrasp::viz::png_detail {

namespace {
// libpng reports an error by calling this and expects it not to return: back to the setjmp of
// the function that called into libpng, which then gives up. Nothing is printed: the caller
// turns a failure into its own message (or into OpenCV's, see png_codec.hpp).
[[noreturn]] void fail(png_structp p, png_const_charp) { png_longjmp(p, 1); }
void ignore(png_structp, png_const_charp) {}

constexpr bool kLittleEndian = std::endian::native == std::endian::little;

// Appends libpng's output to the vector behind the io pointer; out of memory is libpng's error.
void append(png_structp p, png_bytep data, png_size_t n) {
  auto* out = static_cast<std::vector<std::uint8_t>*>(png_get_io_ptr(p));
  try {
    out->insert(out->end(), data, data + n);
  } catch (const std::bad_alloc&) {
    png_error(p, "out of memory");
  }
}
void flush(png_structp) {}

// The libpng calls of a write, with only plain values alive across the setjmp. `rows` are the
// image's rows as OpenCV keeps them: BGR(A) and, for 16 bits, the machine's byte order.
bool write_png(png_uint_32 width, png_uint_32 height, int bits, int colour, png_bytepp rows,
               std::vector<std::uint8_t>* out) {
  png_structp p = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, fail, ignore);
  if (p == nullptr) return false;
  png_infop info = png_create_info_struct(p);
  if (info == nullptr || setjmp(png_jmpbuf(p))) {
    png_destroy_write_struct(&p, &info);
    return false;
  }
  png_set_write_fn(p, out, append, flush);
  png_set_IHDR(p, info, width, height, bits, colour, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  // imencode's defaults (grfmt_png.cpp, no compression level asked): tuned for speed.
  png_set_filter(p, PNG_FILTER_TYPE_BASE, PNG_FILTER_SUB);
  png_set_compression_level(p, Z_BEST_SPEED);
  png_set_compression_strategy(p, Z_RLE);
  png_write_info(p, info);
  if (colour != PNG_COLOR_TYPE_GRAY) png_set_bgr(p);
  if (bits == 16 && kLittleEndian) png_set_swap(p);
  png_write_image(p, rows);
  png_write_end(p, nullptr);
  png_destroy_write_struct(&p, &info);
  return true;
}

struct Header {
  png_uint_32 width = 0, height = 0;
  int bits = 0, colour = 0;
  bool transparency = false;
};

// One read: libpng's structures and the file, released however the read ends.
struct Reader {
  std::FILE* file = nullptr;
  png_structp p = nullptr;
  png_infop info = nullptr;
  ~Reader() {
    if (p != nullptr) png_destroy_read_struct(&p, &info, nullptr);
    if (file != nullptr) std::fclose(file);
  }
};

bool read_header(Reader& r, Header& h) {
  if (setjmp(png_jmpbuf(r.p))) return false;
  png_init_io(r.p, r.file);
  png_set_sig_bytes(r.p, 8);
  png_read_info(r.p, r.info);
  int interlace = 0, compression = 0, filter = 0;
  png_get_IHDR(r.p, r.info, &h.width, &h.height, &h.bits, &h.colour, &interlace, &compression,
               &filter);
  h.transparency = png_get_valid(r.p, r.info, PNG_INFO_tRNS) != 0;
  return true;
}

// The rows, as imread's PNG decoder sets libpng up for them (BGR, the machine's byte order).
bool read_rows(Reader& r, int colour, int bits, png_bytepp rows, bool& exif) {
  if (setjmp(png_jmpbuf(r.p))) return false;
  if (colour != PNG_COLOR_TYPE_GRAY) png_set_bgr(r.p);
  if (bits == 16 && kLittleEndian) png_set_swap(r.p);
  png_set_interlace_handling(r.p);
  png_read_update_info(r.p, r.info);
  png_read_image(r.p, rows);
  png_read_end(r.p, r.info);
  exif = png_get_valid(r.p, r.info, PNG_INFO_eXIf) != 0;
  return true;
}

// The Mat type imread gives this PNG with these flags where no conversion is involved; -1 where
// there is one (or a palette, transparency, fewer than 8 bits), which is OpenCV's to do.
int plain_type(const Header& h, int flags) {
  if (h.transparency || (h.bits != 8 && h.bits != 16)) return -1;
  const int depth = h.bits == 16 ? CV_16U : CV_8U;
  if (h.colour == PNG_COLOR_TYPE_GRAY) {
    if (flags == cv::IMREAD_UNCHANGED || flags == cv::IMREAD_ANYDEPTH) return CV_MAKETYPE(depth, 1);
    return flags == cv::IMREAD_GRAYSCALE && h.bits == 8 ? CV_8UC1 : -1;
  }
  if (flags != cv::IMREAD_UNCHANGED) return -1;
  if (h.colour == PNG_COLOR_TYPE_RGB) return CV_MAKETYPE(depth, 3);
  if (h.colour == PNG_COLOR_TYPE_RGB_ALPHA) return CV_MAKETYPE(depth, 4);
  return -1;
}
}  // namespace

bool encode(const cv::Mat& image, std::vector<std::uint8_t>& out) {
  out.clear();
  const int channels = image.channels();
  if (image.empty() || image.dims != 2 || (image.depth() != CV_8U && image.depth() != CV_16U) ||
      (channels != 1 && channels != 3 && channels != 4))
    return false;
  std::vector<png_bytep> rows(std::size_t(image.rows));
  for (int v = 0; v < image.rows; ++v)
    rows[std::size_t(v)] = const_cast<png_bytep>(image.ptr<png_byte>(v));
  const int colour = channels == 1   ? PNG_COLOR_TYPE_GRAY
                     : channels == 3 ? PNG_COLOR_TYPE_RGB
                                     : PNG_COLOR_TYPE_RGB_ALPHA;
  out.reserve(image.total() * image.elemSize() / 4 + 1024);
  if (write_png(png_uint_32(image.cols), png_uint_32(image.rows), image.depth() == CV_16U ? 16 : 8,
                colour, rows.data(), &out))
    return true;
  out.clear();
  return false;
}

std::optional<cv::Mat> decode(const std::string& path, int flags) {
  Reader r;
  r.file = std::fopen(path.c_str(), "rb");
  png_byte signature[8];
  if (r.file == nullptr || std::fread(signature, 1, 8, r.file) != 8 ||
      png_sig_cmp(signature, 0, 8) != 0)
    return std::nullopt;
  r.p = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, fail, ignore);
  if (r.p == nullptr) return std::nullopt;
  r.info = png_create_info_struct(r.p);
  Header h;
  if (r.info == nullptr || !read_header(r, h)) return std::nullopt;
  const int type = plain_type(h, flags);
  // OpenCV's own limit is 2^30 pixels (CV_IO_MAX_IMAGE_PIXELS): beyond it, its refusal.
  if (type < 0 || h.width == 0 || h.height == 0 ||
      double(h.width) * double(h.height) > double(1 << 30))
    return std::nullopt;
  // A header that asks for more pixels than the file could hold (deflate turns one byte of file
  // into at most ~1032 of image) belongs to a truncated or hostile file: not worth a frame-sized
  // allocation.
  std::error_code ec;
  const double file = double(std::filesystem::file_size(path, ec));
  const double raw = double(h.height) * (1.0 + double(h.width) * double(CV_ELEM_SIZE(type)));
  if (ec || raw > 1100.0 * file + 4096.0) return std::nullopt;
  cv::Mat m;
  try {
    m.create(int(h.height), int(h.width), type);
  } catch (const cv::Exception&) {
    return std::nullopt;  // out of memory: OpenCV's codec reports it as a file it cannot read
  }
  std::vector<png_bytep> rows(std::size_t(m.rows));
  for (int v = 0; v < m.rows; ++v) rows[std::size_t(v)] = m.ptr<png_byte>(v);
  bool exif = false;
  if (!read_rows(r, h.colour, h.bits, rows.data(), exif)) return std::nullopt;
  // imread turns an image by its EXIF orientation unless the flags are IMREAD_UNCHANGED.
  if (exif && flags != cv::IMREAD_UNCHANGED) return std::nullopt;
  return m;
}

}  // namespace uwgrasp::viz::png_detail

#include "alloycolor/render/image.h"

#include <png.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

#include "alloycolor/color/colorimetry.h"
#include "alloycolor/core/error.h"
#include "alloycolor/core/io.h"

namespace alloycolor::render {
namespace {

// Exact and fast 8-bit sRGB encoding of a float: code k + 1 begins at the smallest float v
// with round(255 SRGBEncode(v)) > k, found once by bisection on the floats; a coarse table
// gives the code at the start of each of kBins bins, and the thresholds finish the job.
class SRGB8Encoder {
 public:
  static const SRGB8Encoder& Get() {
    static const SRGB8Encoder kEncoder;
    return kEncoder;
  }

  std::uint8_t Encode(float linear) const {
    // NaN and negatives end up as 0, like SRGB8FromLinear.
    if (!(linear > 0.0f)) return 0;
    if (linear >= 1.0f) return 255;
    int code = start_[static_cast<int>(linear * kBins)];
    while (code < 255 && linear >= threshold_[code]) ++code;
    return static_cast<std::uint8_t>(code);
  }

 private:
  static constexpr int kBins = 4096;

  static int Code(float v) {
    const double clamped = std::clamp(static_cast<double>(v), 0.0, 1.0);
    return static_cast<int>(std::lround(255.0 * color::SRGBEncode(clamped)));
  }

  SRGB8Encoder() {
    for (int k = 0; k < 255; ++k) {
      // Bisection over the ordered bit patterns of the non-negative floats in [0, 1].
      std::uint32_t lo = 0, hi = 0x3f800000u;  // 0.0f, 1.0f
      while (hi - lo > 1) {
        const std::uint32_t mid = lo + (hi - lo) / 2;
        float v;
        std::memcpy(&v, &mid, sizeof v);
        (Code(v) > k ? hi : lo) = mid;
      }
      std::memcpy(&threshold_[k], &hi, sizeof(float));
    }
    for (int i = 0; i < kBins; ++i) start_[i] = Code(static_cast<float>(i) / kBins);
  }

  std::array<float, 255> threshold_{};
  std::array<std::uint8_t, kBins> start_{};
};

std::uint16_t EncodeSRGB16Sample(float linear) {
  const double clamped = linear > 0.0f ? std::min(static_cast<double>(linear), 1.0) : 0.0;
  return static_cast<std::uint16_t>(std::lround(65535.0 * color::SRGBEncode(clamped)));
}

template <typename T>
T QuantiseAlpha(float alpha) {
  constexpr double kMax = std::numeric_limits<T>::max();
  const double clamped = alpha > 0.0f ? std::min(static_cast<double>(alpha), 1.0) : 0.0;
  return static_cast<T>(std::lround(kMax * clamped));
}

void CheckImage(int width, int height, std::size_t samples) {
  if (width <= 0 || height <= 0 || samples != static_cast<std::size_t>(width) * height * 4) {
    throw Error("PNG: the image is empty or its sample count does not match " +
                std::to_string(width) + "x" + std::to_string(height));
  }
}

// What the libpng writer needs, as plain data (it runs under setjmp).
struct PngJob {
  png_uint_32 width;
  png_uint_32 height;
  int bit_depth;
  png_bytep* rows;
  png_textp text;
  int text_count;
  bool srgb;  // the sRGB, gAMA and cHRM chunks (not for data such as a lookup table)
};

void WriteCallback(png_structp png, png_bytep data, png_size_t length) {
  auto* out = static_cast<std::string*>(png_get_io_ptr(png));
  try {
    out->append(reinterpret_cast<const char*>(data), length);
  } catch (...) {
    png_error(png, "out of memory");
  }
}

void ErrorCallback(png_structp png, png_const_charp message) {
  char* error = static_cast<char*>(png_get_error_ptr(png));
  std::snprintf(error, 256, "%s", message);
  png_longjmp(png, 1);
}

void WarningCallback(png_structp, png_const_charp) {}

// Returns false with a message in error[256] when libpng fails.
bool RunPngWriter(const PngJob& job, std::string* out, char* error) {
  png_structp png =
      png_create_write_struct(PNG_LIBPNG_VER_STRING, error, ErrorCallback, WarningCallback);
  if (png == nullptr) {
    std::snprintf(error, 256, "cannot start libpng");
    return false;
  }
  png_infop info = png_create_info_struct(png);
  if (info == nullptr) {
    png_destroy_write_struct(&png, nullptr);
    std::snprintf(error, 256, "cannot start libpng");
    return false;
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  png_set_write_fn(png, out, WriteCallback, nullptr);
  png_set_IHDR(png, info, job.width, job.height, job.bit_depth, PNG_COLOR_TYPE_RGB_ALPHA,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  if (job.srgb) png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
  if (job.text_count > 0) png_set_text(png, info, job.text, job.text_count);
  png_write_info(png, info);
  png_write_image(png, job.rows);
  png_write_end(png, info);
  png_destroy_write_struct(&png, &info);
  return true;
}

// bytes (only read): rows of width * 4 samples of bit_depth / 8 bytes each, big-endian.
std::string EncodePng(int width, int height, int bit_depth, png_byte* bytes,
                      const std::vector<PngText>& text, bool srgb = true) {
  const std::size_t row_bytes = static_cast<std::size_t>(width) * 4 * (bit_depth / 8);
  std::vector<png_bytep> rows(height);
  for (int y = 0; y < height; ++y) rows[y] = bytes + row_bytes * y;
  std::vector<std::string> keys, values;
  keys.reserve(text.size());
  values.reserve(text.size());
  std::vector<png_text> chunks(text.size());
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i].keyword.empty() || text[i].keyword.size() > 79) {
      throw Error("PNG: text keyword '" + text[i].keyword + "' must have 1-79 characters");
    }
    keys.push_back(text[i].keyword);
    values.push_back(text[i].text);
    chunks[i] = png_text{};
    chunks[i].compression = PNG_TEXT_COMPRESSION_NONE;
    chunks[i].key = keys.back().data();
    chunks[i].text = values.back().data();
    chunks[i].text_length = values.back().size();
  }
  const PngJob job{static_cast<png_uint_32>(width),
                   static_cast<png_uint_32>(height),
                   bit_depth,
                   rows.data(),
                   chunks.data(),
                   static_cast<int>(chunks.size()),
                   srgb};
  std::string out;
  out.reserve(row_bytes * height / 2);
  char error[256] = "";
  if (!RunPngWriter(job, &out, error)) throw Error(std::string("PNG: libpng: ") + error);
  return out;
}

}  // namespace

ImageRGBA8 EncodeSRGB8(const LinearImage& image) {
  const SRGB8Encoder& encoder = SRGB8Encoder::Get();
  ImageRGBA8 out(image.width, image.height);
  const std::size_t n = out.rgba.size();
  for (std::size_t i = 0; i < n; i += 4) {
    out.rgba[i] = encoder.Encode(image.rgba[i]);
    out.rgba[i + 1] = encoder.Encode(image.rgba[i + 1]);
    out.rgba[i + 2] = encoder.Encode(image.rgba[i + 2]);
    out.rgba[i + 3] = QuantiseAlpha<std::uint8_t>(image.rgba[i + 3]);
  }
  return out;
}

ImageRGBA16 EncodeSRGB16(const LinearImage& image) {
  ImageRGBA16 out(image.width, image.height);
  const std::size_t n = out.rgba.size();
  for (std::size_t i = 0; i < n; i += 4) {
    out.rgba[i] = EncodeSRGB16Sample(image.rgba[i]);
    out.rgba[i + 1] = EncodeSRGB16Sample(image.rgba[i + 1]);
    out.rgba[i + 2] = EncodeSRGB16Sample(image.rgba[i + 2]);
    out.rgba[i + 3] = QuantiseAlpha<std::uint16_t>(image.rgba[i + 3]);
  }
  return out;
}

void Paste(const LinearImage& tile, int x0, int y0, LinearImage* image) {
  if (x0 < 0 || y0 < 0 || x0 + tile.width > image->width || y0 + tile.height > image->height) {
    throw Error("Paste: the tile does not fit in the image");
  }
  for (int y = 0; y < tile.height; ++y) {
    std::copy(tile.Pixel(0, y), tile.Pixel(0, y) + 4 * tile.width, image->Pixel(x0, y0 + y));
  }
}

std::string PngBytes(const ImageRGBA8& image, const std::vector<PngText>& text) {
  CheckImage(image.width, image.height, image.rgba.size());
  // libpng only reads the rows it is given.
  return EncodePng(image.width, image.height, 8, const_cast<png_byte*>(image.rgba.data()), text);
}

namespace {

std::string Png16Bytes(const ImageRGBA16& image, const std::vector<PngText>& text, bool srgb) {
  CheckImage(image.width, image.height, image.rgba.size());
  std::vector<png_byte> bytes(image.rgba.size() * 2);
  for (std::size_t i = 0; i < image.rgba.size(); ++i) {
    bytes[2 * i] = static_cast<png_byte>(image.rgba[i] >> 8);
    bytes[2 * i + 1] = static_cast<png_byte>(image.rgba[i] & 0xff);
  }
  return EncodePng(image.width, image.height, 16, bytes.data(), text, srgb);
}

}  // namespace

std::string PngBytes(const ImageRGBA16& image, const std::vector<PngText>& text) {
  return Png16Bytes(image, text, true);
}

std::string DataPngBytes(const ImageRGBA16& image, const std::vector<PngText>& text) {
  return Png16Bytes(image, text, false);
}

void WritePng(const std::string& path, const ImageRGBA8& image, const std::vector<PngText>& text) {
  WriteFileAtomic(path, PngBytes(image, text));
}

void WritePng(const std::string& path, const ImageRGBA16& image, const std::vector<PngText>& text) {
  WriteFileAtomic(path, PngBytes(image, text));
}

}  // namespace alloycolor::render

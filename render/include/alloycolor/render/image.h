// Images and PNG files.
//
// An image holds RGBA samples interleaved, top row first, with straight (not premultiplied)
// alpha. The renderer produces a LinearImage: linear sRGB (IEC 61966-2-1 primaries, D65
// white, Y = 1 for a perfect reflector) and alpha = the pixel's coverage in [0, 1]. It is
// encoded for a file with the sRGB transfer function, clamped to [0, 1] and rounded to 8
// or 16 bits, exactly as SRGB8FromLinear in colorimetry.h.
//
// PNG files are written with libpng, colour type RGBA, 8 or 16 bits per sample, carrying
// an sRGB chunk (rendering intent perceptual) and the gAMA and cHRM chunks the PNG
// specification (ISO/IEC 15948, 11.3.3.5) recommends alongside it, plus optional tEXt
// chunks. Files are written to a temporary file renamed into place, so a failure never
// leaves a damaged file.
#ifndef ALLOYCOLOR_RENDER_IMAGE_H_
#define ALLOYCOLOR_RENDER_IMAGE_H_

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace alloycolor::render {

template <typename T>
struct ImageRGBA {
  int width = 0;
  int height = 0;
  std::vector<T> rgba;  // width * height * 4 samples

  ImageRGBA() = default;
  ImageRGBA(int w, int h) : width(w), height(h), rgba(static_cast<std::size_t>(w) * h * 4) {}
  T* Pixel(int x, int y) { return &rgba[(static_cast<std::size_t>(y) * width + x) * 4]; }
  const T* Pixel(int x, int y) const {
    return &rgba[(static_cast<std::size_t>(y) * width + x) * 4];
  }
};

using LinearImage = ImageRGBA<float>;
using ImageRGBA8 = ImageRGBA<std::uint8_t>;
using ImageRGBA16 = ImageRGBA<std::uint16_t>;

// sRGB-encoded samples; alpha is quantised linearly. Exact: each sample is
// round(max * SRGBEncode(clamp(value, 0, 1))).
ImageRGBA8 EncodeSRGB8(const LinearImage& image);
ImageRGBA16 EncodeSRGB16(const LinearImage& image);

// Copies `tile` into `image` with its top-left corner at (x0, y0); the tile must fit.
void Paste(const LinearImage& tile, int x0, int y0, LinearImage* image);

// A tEXt chunk: keyword (1-79 Latin-1 characters) and text.
struct PngText {
  std::string keyword;
  std::string text;
};

// The PNG file's bytes. Throws Error for an empty image or a libpng failure.
std::string PngBytes(const ImageRGBA8& image, const std::vector<PngText>& text = {});
std::string PngBytes(const ImageRGBA16& image, const std::vector<PngText>& text = {});
// A 16-bit PNG of data rather than an sRGB picture (linear values, a lookup table): the
// samples as they are, without the sRGB, gAMA and cHRM chunks.
std::string DataPngBytes(const ImageRGBA16& image, const std::vector<PngText>& text = {});

// Writes the PNG file atomically; throws Error naming the path when it cannot.
void WritePng(const std::string& path, const ImageRGBA8& image,
              const std::vector<PngText>& text = {});
void WritePng(const std::string& path, const ImageRGBA16& image,
              const std::vector<PngText>& text = {});

}  // namespace alloycolor::render

#endif  // ALLOYCOLOR_RENDER_IMAGE_H_

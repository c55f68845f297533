// A minimal PNG encoder (8-bit RGB, zlib deflate, no filtering): the report's pictures are
// written by the program itself, with nothing beyond zlib.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace jawmesh {

/// An 8-bit RGB image, row-major from the top row, 3 bytes per pixel.
struct RgbImage {
    int width = 0, height = 0;
    std::vector<std::uint8_t> rgb;
};

/// The PNG file bytes of `image` (IHDR, one IDAT, IEND; CRCs by zlib's crc32).
/// Throws Error for an empty image or a pixel buffer of the wrong size. Cost: O(pixels).
std::string encodePng(const RgbImage& image);

/// encodePng() written atomically to `path`. Throws Error on I/O failure.
void writePng(const RgbImage& image, const std::string& path);

/// Base64 of arbitrary bytes (for data: URIs in self-contained HTML). Cost: O(bytes).
std::string base64(const std::string& bytes);

}  // namespace jawmesh

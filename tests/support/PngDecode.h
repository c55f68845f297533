// A small PNG decoder for tests (8-bit RGB/RGBA, non-interlaced, all five row filters): enough to
// read back our own pictures and Chromium's screenshots.
#pragma once

#include <zlib.h>

#include <array>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

namespace jawmesh::test {

struct DecodedPng {
    int width = 0, height = 0;
    std::vector<std::array<std::uint8_t, 3>> rgb;  ///< row-major, alpha dropped
};

inline DecodedPng decodePng(const std::string& png) {
    const auto be32 = [&](std::size_t at) {
        return (std::uint32_t(std::uint8_t(png.at(at))) << 24) | (std::uint32_t(std::uint8_t(png.at(at + 1))) << 16) |
               (std::uint32_t(std::uint8_t(png.at(at + 2))) << 8) | std::uint32_t(std::uint8_t(png.at(at + 3)));
    };
    if (png.size() < 8 || png.compare(0, 8, std::string("\x89PNG\r\n\x1a\n", 8)) != 0) throw std::runtime_error("not a PNG");
    DecodedPng out;
    int channels = 0;
    std::string idat;
    for (std::size_t at = 8; at + 8 <= png.size();) {
        const std::uint32_t len = be32(at);
        const std::string type = png.substr(at + 4, 4);
        if (type == "IHDR") {
            out.width = static_cast<int>(be32(at + 8));
            out.height = static_cast<int>(be32(at + 12));
            const int depth = std::uint8_t(png.at(at + 16)), colour = std::uint8_t(png.at(at + 17)), interlace = std::uint8_t(png.at(at + 20));
            if (depth != 8 || (colour != 2 && colour != 6) || interlace != 0) throw std::runtime_error("unsupported PNG format");
            channels = colour == 2 ? 3 : 4;
        } else if (type == "IDAT") {
            idat += png.substr(at + 8, len);
        }
        at += 12 + len;
    }
    const std::size_t stride = static_cast<std::size_t>(out.width) * static_cast<std::size_t>(channels);
    std::vector<std::uint8_t> raw((stride + 1) * static_cast<std::size_t>(out.height));
    uLongf size = static_cast<uLongf>(raw.size());
    if (uncompress(raw.data(), &size, reinterpret_cast<const Bytef*>(idat.data()), static_cast<uLong>(idat.size())) != Z_OK || size != raw.size())
        throw std::runtime_error("bad PNG data");
    std::vector<std::uint8_t> cur(stride), prev(stride, 0);
    const std::size_t bpp = static_cast<std::size_t>(channels);
    for (int y = 0; y < out.height; ++y) {
        const std::uint8_t* row = raw.data() + static_cast<std::size_t>(y) * (stride + 1);
        const int filter = row[0];
        for (std::size_t i = 0; i < stride; ++i) {
            const int a = i >= bpp ? cur[i - bpp] : 0, b = prev[i], c = i >= bpp ? prev[i - bpp] : 0;
            int pred = 0;
            switch (filter) {
            case 0: pred = 0; break;
            case 1: pred = a; break;
            case 2: pred = b; break;
            case 3: pred = (a + b) / 2; break;
            case 4: {
                const int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
                pred = pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
                break;
            }
            default: throw std::runtime_error("bad PNG filter");
            }
            cur[i] = static_cast<std::uint8_t>(row[1 + i] + pred);
        }
        for (int x = 0; x < out.width; ++x) {
            const std::size_t o = static_cast<std::size_t>(x) * bpp;
            out.rgb.push_back({cur[o], cur[o + 1], cur[o + 2]});
        }
        std::swap(cur, prev);
    }
    return out;
}

}  // namespace jawmesh::test

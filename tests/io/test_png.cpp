// encodePng(): the file decodes back (signature, chunk CRCs, zlib stream) to the same pixels.
#include "io/Error.h"
#include "io/PngWriter.h"

#include <gtest/gtest.h>
#include <zlib.h>

#include <cstring>

using namespace jawmesh;

namespace {
std::uint32_t be32(const std::string& s, std::size_t at) {
    return (std::uint32_t(static_cast<unsigned char>(s[at])) << 24) | (std::uint32_t(static_cast<unsigned char>(s[at + 1])) << 16) |
           (std::uint32_t(static_cast<unsigned char>(s[at + 2])) << 8) | std::uint32_t(static_cast<unsigned char>(s[at + 3]));
}
}  // namespace

TEST(Png, RoundTripsThroughZlib) {
    RgbImage img;
    img.width = 37;
    img.height = 11;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            for (int c = 0; c < 3; ++c) img.rgb.push_back(static_cast<std::uint8_t>((x * 7 + y * 13 + c * 50) & 0xff));
    const std::string png = encodePng(img);
    ASSERT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
    std::size_t at = 8;
    std::string idat, types;
    while (at < png.size()) {
        const std::uint32_t len = be32(png, at);
        const std::string type = png.substr(at + 4, 4);
        const std::string body = png.substr(at + 4, 4 + len);
        EXPECT_EQ(be32(png, at + 8 + len), crc32(0, reinterpret_cast<const Bytef*>(body.data()), static_cast<uInt>(body.size()))) << type;
        if (type == "IHDR") {
            EXPECT_EQ(be32(png, at + 8), 37u);
            EXPECT_EQ(be32(png, at + 12), 11u);
        }
        if (type == "IDAT") idat += png.substr(at + 8, len);
        types += type + " ";
        at += 12 + len;
    }
    EXPECT_EQ(types, "IHDR IDAT IEND ");
    std::string raw((3 * 37 + 1) * 11, '\0');
    uLongf size = static_cast<uLongf>(raw.size());
    ASSERT_EQ(uncompress(reinterpret_cast<Bytef*>(&raw[0]), &size, reinterpret_cast<const Bytef*>(idat.data()), static_cast<uLong>(idat.size())), Z_OK);
    ASSERT_EQ(size, raw.size());
    for (int y = 0; y < 11; ++y) {
        EXPECT_EQ(raw[static_cast<std::size_t>(y) * (3 * 37 + 1)], '\0');  // filter type none
        EXPECT_EQ(0, std::memcmp(&raw[static_cast<std::size_t>(y) * (3 * 37 + 1) + 1], img.rgb.data() + y * 3 * 37, 3 * 37));
    }
    img.rgb.pop_back();
    EXPECT_THROW(encodePng(img), Error);
    EXPECT_EQ(base64("Man"), "TWFu");
    EXPECT_EQ(base64("Ma"), "TWE=");
    EXPECT_EQ(base64("M"), "TQ==");
}

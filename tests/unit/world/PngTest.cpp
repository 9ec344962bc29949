// The PNG encoder: checksums against known values, a well-formed file layout, compression, and a lossless round
// trip through decodePng.
#include "robot/world/PngWriter.h"

#include <gtest/gtest.h>

#include <cstring>

namespace cbtl::world {
namespace {

TEST(WorldPng, ChecksumsMatchKnownValues) {
  const char* text = "123456789";
  const auto* bytes = reinterpret_cast<const std::uint8_t*>(text);
  EXPECT_EQ(crc32(bytes, 9), 0xCBF43926U);
  const char* wiki = "Wikipedia";
  EXPECT_EQ(adler32(reinterpret_cast<const std::uint8_t*>(wiki), std::strlen(wiki)), 0x11E60398U);
}

TEST(WorldPng, LayoutIsSignatureIhdrIdatIend) {
  const std::vector<std::uint8_t> rgb(4 * 2 * 3, 200);
  const auto png = encodePng(4, 2, rgb);
  ASSERT_GT(png.size(), 8U + 25U + 12U);
  const std::uint8_t sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  EXPECT_EQ(std::memcmp(png.data(), sig, 8), 0);
  EXPECT_EQ(std::memcmp(png.data() + 12, "IHDR", 4), 0);
  EXPECT_EQ(png[16 + 3], 4);  // width
  EXPECT_EQ(png[20 + 3], 2);  // height
  EXPECT_EQ(std::memcmp(png.data() + 33 + 4, "IDAT", 4), 0);
  EXPECT_EQ(std::memcmp(png.data() + png.size() - 8, "IEND", 4), 0);
  // IHDR's CRC covers its type and data.
  const std::uint32_t crc =
      (std::uint32_t{png[29]} << 24) | (std::uint32_t{png[30]} << 16) | (std::uint32_t{png[31]} << 8) | png[32];
  EXPECT_EQ(crc, crc32(png.data() + 12, 17));
}

TEST(WorldPng, RoundTripsThroughEveryFilter) {
  // A gradient, a flat band and noise: rows where None, Sub, Up, Average and Paeth each win.
  const int w = 97, h = 61;
  std::vector<std::uint8_t> rgb(static_cast<std::size_t>(w * h * 3));
  std::uint32_t noise = 12345;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int k = 0; k < 3; ++k) {
        noise = noise * 1103515245U + 12345U;
        const auto at = static_cast<std::size_t>((y * w + x) * 3 + k);
        rgb[at] = y < 20 ? static_cast<std::uint8_t>(x * 2 + k) : y < 40 ? 90 : static_cast<std::uint8_t>(noise >> 24);
      }
  const auto png = encodePng(w, h, rgb);
  const auto back = decodePng(png);
  ASSERT_TRUE(back.has_value());
  EXPECT_EQ(back->width, w);
  EXPECT_EQ(back->height, h);
  EXPECT_EQ(back->rgb, rgb);
  std::vector<std::uint8_t> broken = png;
  broken[40] ^= 0xFF;  // inside IDAT: its CRC no longer matches
  EXPECT_FALSE(decodePng(broken).has_value());
}

TEST(WorldPng, FlatImagesCompress) {
  const std::vector<std::uint8_t> rgb(320 * 240 * 3, 7);
  const auto png = encodePng(320, 240, rgb);
  EXPECT_LT(png.size(), 2000U) << "230,400 bytes of one colour";
  EXPECT_TRUE(encodePng(0, 10, rgb).empty());
  EXPECT_TRUE(encodePng(10, 10, {}).empty());
}

}  // namespace
}  // namespace cbtl::world

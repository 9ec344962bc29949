// The PNG encoder: checksums against known values and a well-formed file layout.
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

TEST(WorldPng, LargeImagesSpanSeveralStoredBlocks) {
  const std::vector<std::uint8_t> rgb(300 * 200 * 3, 7);
  const auto png = encodePng(300, 200, rgb);
  // 200 rows of 901 bytes = 180200 raw bytes: three stored blocks of 5 header bytes each, zlib header and
  // Adler-32, 12 bytes of IDAT framing, plus the signature, IHDR and IEND.
  EXPECT_EQ(png.size(), 8U + 25U + (12U + 2U + 180200U + 3U * 5U + 4U) + 12U);
  EXPECT_TRUE(encodePng(0, 10, rgb).empty());
  EXPECT_TRUE(encodePng(10, 10, {}).empty());
}

}  // namespace
}  // namespace cbtl::world

// PngWriter.h — a minimal PNG encoder: 8-bit RGB, no filtering, zlib stream of stored (uncompressed)
// deflate blocks, with the CRC-32 and Adler-32 checksums the format requires. Files are larger than a
// compressing encoder's but valid for every PNG reader; no image library is a project dependency.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace cbtl::world {

// rgb: width*height*3 bytes, rows top to bottom. Returns the PNG file bytes (empty if the size is 0 or the
// buffer is too small).
std::vector<std::uint8_t> encodePng(int width, int height, const std::vector<std::uint8_t>& rgb);

// Writes encodePng(...) to `path`; false if encoding or writing fails.
bool writePng(const std::string& path, int width, int height, const std::vector<std::uint8_t>& rgb);

std::uint32_t crc32(const std::uint8_t* data, std::size_t size, std::uint32_t crc = 0);
std::uint32_t adler32(const std::uint8_t* data, std::size_t size);

}  // namespace cbtl::world

// PngWriter.h — a small PNG encoder: 8-bit RGB, each scanline with the filter the specification's heuristic picks,
// compressed with zlib (Debian's, already a dependency of the run record). A 320 x 240 rendered scene is about
// 20 KB instead of the 230 KB of its raw pixels; no image library is a project dependency.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace cbtl::world {

// rgb: width*height*3 bytes, rows top to bottom. Returns the PNG file bytes (empty if the size is 0 or the
// buffer is too small).
std::vector<std::uint8_t> encodePng(int width, int height, const std::vector<std::uint8_t>& rgb);

// What encodePng wrote, read back (8-bit RGB, any filters, checksums checked); nullopt for anything else. For tests
// and checks of pictures, not a general PNG reader.
struct DecodedPng {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;
};
std::optional<DecodedPng> decodePng(const std::vector<std::uint8_t>& png);

// Writes encodePng(...) to `path`; false if encoding or writing fails.
bool writePng(const std::string& path, int width, int height, const std::vector<std::uint8_t>& rgb);

// The value PNG filter `filter` (0 None, 1 Sub, 2 Up, 3 Average, 4 Paeth) predicts a byte from: `a` the byte one
// pixel to the left, `b` the byte above, `c` the byte above-left (0 outside the image). Decoders add it back.
int filterPredictor(int filter, int a, int b, int c);

std::uint32_t crc32(const std::uint8_t* data, std::size_t size, std::uint32_t crc = 0);
std::uint32_t adler32(const std::uint8_t* data, std::size_t size);

}  // namespace cbtl::world

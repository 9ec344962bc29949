#include "robot/world/PngWriter.h"

#include <zlib.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <fstream>
#include <string>

namespace cbtl::world {

namespace {

std::array<std::uint32_t, 256> makeCrcTable() {
  std::array<std::uint32_t, 256> table{};
  for (std::uint32_t n = 0; n < 256; ++n) {
    std::uint32_t c = n;
    for (int k = 0; k < 8; ++k) c = (c & 1U) ? 0xEDB88320U ^ (c >> 1) : c >> 1;
    table[n] = c;
  }
  return table;
}

void put32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  out.push_back(static_cast<std::uint8_t>(v >> 24));
  out.push_back(static_cast<std::uint8_t>(v >> 16));
  out.push_back(static_cast<std::uint8_t>(v >> 8));
  out.push_back(static_cast<std::uint8_t>(v));
}

// Length, type, data, CRC over type and data.
void putChunk(std::vector<std::uint8_t>& out, const char type[4], const std::vector<std::uint8_t>& data) {
  put32(out, static_cast<std::uint32_t>(data.size()));
  const std::size_t typeAt = out.size();
  out.insert(out.end(), type, type + 4);
  out.insert(out.end(), data.begin(), data.end());
  put32(out, crc32(out.data() + typeAt, 4 + data.size()));
}

}  // namespace

std::uint32_t crc32(const std::uint8_t* data, std::size_t size, std::uint32_t crc) {
  static const auto table = makeCrcTable();
  crc = ~crc;
  for (std::size_t i = 0; i < size; ++i) crc = table[(crc ^ data[i]) & 0xFFU] ^ (crc >> 8);
  return ~crc;
}

std::uint32_t adler32(const std::uint8_t* data, std::size_t size) {
  constexpr std::uint32_t kMod = 65521;
  std::uint32_t a = 1, b = 0;
  for (std::size_t i = 0; i < size; ++i) {
    a = (a + data[i]) % kMod;
    b = (b + a) % kMod;
  }
  return (b << 16) | a;
}

std::vector<std::uint8_t> encodePng(int width, int height, const std::vector<std::uint8_t>& rgb) {
  if (width <= 0 || height <= 0) return {};
  const std::size_t row = static_cast<std::size_t>(width) * 3;
  if (rgb.size() < row * static_cast<std::size_t>(height)) return {};

  // Scanlines, each prefixed with its filter type: of the five, the one whose output has the smallest sum of
  // absolute values (as signed bytes), the heuristic the PNG specification recommends. Rendered scenes, with large
  // flat and smoothly shaded areas, then compress about 25 times.
  std::vector<std::uint8_t> raw;
  raw.reserve((row + 1) * static_cast<std::size_t>(height));
  std::array<std::vector<std::uint8_t>, 5> candidates;
  for (auto& c : candidates) c.resize(row);
  for (int y = 0; y < height; ++y) {
    const std::uint8_t* cur = rgb.data() + static_cast<std::size_t>(y) * row;
    const std::uint8_t* prev = y > 0 ? cur - row : nullptr;
    std::size_t best = 0;
    long bestCost = -1;
    for (std::size_t f = 0; f < candidates.size(); ++f) {
      long cost = 0;
      for (std::size_t i = 0; i < row; ++i) {
        const int a = i >= 3 ? cur[i - 3] : 0, b = prev ? prev[i] : 0, c = prev && i >= 3 ? prev[i - 3] : 0;
        const auto value = static_cast<std::uint8_t>(cur[i] - filterPredictor(static_cast<int>(f), a, b, c));
        candidates[f][i] = value;
        cost += value < 128 ? value : 256 - value;
      }
      if (bestCost < 0 || cost < bestCost) {
        bestCost = cost;
        best = f;
      }
    }
    raw.push_back(static_cast<std::uint8_t>(best));
    raw.insert(raw.end(), candidates[best].begin(), candidates[best].end());
  }

  uLongf zSize = compressBound(static_cast<uLong>(raw.size()));
  std::vector<std::uint8_t> z(zSize);
  if (compress2(z.data(), &zSize, raw.data(), static_cast<uLong>(raw.size()), Z_DEFAULT_COMPRESSION) != Z_OK) return {};
  z.resize(zSize);

  std::vector<std::uint8_t> png{0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  std::vector<std::uint8_t> ihdr;
  put32(ihdr, static_cast<std::uint32_t>(width));
  put32(ihdr, static_cast<std::uint32_t>(height));
  ihdr.insert(ihdr.end(), {8, 2, 0, 0, 0});  // bit depth 8, colour type RGB, deflate, adaptive filtering, no interlace
  putChunk(png, "IHDR", ihdr);
  putChunk(png, "IDAT", z);
  putChunk(png, "IEND", {});
  return png;
}

int filterPredictor(int filter, int a, int b, int c) {
  switch (filter) {
    case 1:
      return a;  // Sub
    case 2:
      return b;  // Up
    case 3:
      return (a + b) / 2;  // Average
    case 4: {              // Paeth
      const int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
      return pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
    }
    default:
      return 0;  // None
  }
}

std::optional<DecodedPng> decodePng(const std::vector<std::uint8_t>& png) {
  const std::uint8_t signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  if (png.size() < 8 || !std::equal(signature, signature + 8, png.begin())) return std::nullopt;
  const auto get32 = [&](std::size_t at) {
    return (std::uint32_t{png[at]} << 24) | (std::uint32_t{png[at + 1]} << 16) | (std::uint32_t{png[at + 2]} << 8) |
           png[at + 3];
  };
  DecodedPng out;
  std::vector<std::uint8_t> z;
  for (std::size_t at = 8; at + 12 <= png.size();) {
    const std::uint32_t length = get32(at);
    if (at + 12 + length > png.size()) return std::nullopt;
    const std::string type(png.begin() + static_cast<std::ptrdiff_t>(at + 4),
                           png.begin() + static_cast<std::ptrdiff_t>(at + 8));
    const std::uint8_t* data = png.data() + at + 8;
    if (crc32(png.data() + at + 4, 4 + length) != get32(at + 8 + length)) return std::nullopt;
    if (type == "IHDR") {
      if (length != 13 || data[8] != 8 || data[9] != 2 || data[12] != 0) return std::nullopt;  // 8-bit RGB only
      out.width = static_cast<int>(get32(at + 8));
      out.height = static_cast<int>(get32(at + 12));
    } else if (type == "IDAT") {
      z.insert(z.end(), data, data + length);
    }
    at += 12 + length;
  }
  if (out.width <= 0 || out.height <= 0 || out.width > 1 << 14 || out.height > 1 << 14) return std::nullopt;
  const std::size_t row = static_cast<std::size_t>(out.width) * 3;
  std::vector<std::uint8_t> raw((row + 1) * static_cast<std::size_t>(out.height));
  uLongf rawSize = static_cast<uLongf>(raw.size());
  if (uncompress(raw.data(), &rawSize, z.data(), static_cast<uLong>(z.size())) != Z_OK || rawSize != raw.size())
    return std::nullopt;
  out.rgb.resize(row * static_cast<std::size_t>(out.height));
  for (int y = 0; y < out.height; ++y) {
    const std::uint8_t* in = raw.data() + static_cast<std::size_t>(y) * (row + 1);
    std::uint8_t* cur = out.rgb.data() + static_cast<std::size_t>(y) * row;
    const std::uint8_t* prev = y > 0 ? cur - row : nullptr;
    if (in[0] > 4) return std::nullopt;
    for (std::size_t i = 0; i < row; ++i) {
      const int a = i >= 3 ? cur[i - 3] : 0, b = prev ? prev[i] : 0, c = prev && i >= 3 ? prev[i - 3] : 0;
      cur[i] = static_cast<std::uint8_t>(in[1 + i] + filterPredictor(in[0], a, b, c));
    }
  }
  return out;
}

bool writePng(const std::string& path, int width, int height, const std::vector<std::uint8_t>& rgb) {
  const auto bytes = encodePng(width, height, rgb);
  if (bytes.empty()) return false;
  std::ofstream out(path, std::ios::binary);
  if (!out) return false;
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  return static_cast<bool>(out);
}

}  // namespace cbtl::world

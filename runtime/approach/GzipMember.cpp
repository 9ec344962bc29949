#include "runtime/approach/GzipMember.h"

#include <zlib.h>

#include <stdexcept>

namespace cbtl::approach {

std::string gzipMember(const std::string& text) {
  z_stream z{};
  // windowBits 15 + 16: a gzip header and trailer; memLevel 8 is zlib's default.
  if (deflateInit2(&z, 6, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY) != Z_OK)
    throw std::runtime_error("zlib: cannot start compressing");
  std::string out(deflateBound(&z, static_cast<uLong>(text.size())) + 32, '\0');
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(text.data()));
  z.avail_in = static_cast<uInt>(text.size());
  z.next_out = reinterpret_cast<Bytef*>(out.data());
  z.avail_out = static_cast<uInt>(out.size());
  const int rc = deflate(&z, Z_FINISH);
  const std::size_t written = out.size() - z.avail_out;
  deflateEnd(&z);
  if (rc != Z_STREAM_END) throw std::runtime_error("zlib: compressing failed");
  out.resize(written);
  return out;
}

}  // namespace cbtl::approach

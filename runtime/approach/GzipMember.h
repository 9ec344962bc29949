// GzipMember.h — text compressed as one complete gzip member (RFC 1952), for append-only files that grow by whole
// members: a file of concatenated members is itself valid gzip (`zcat` and zlib's gzread read it whole), and cutting
// it at a member boundary leaves a valid file, which is what a resumed run does (Checkpoint.h). Deterministic: the
// same text gives the same bytes (no timestamp or file name in the header, fixed compression level).
#pragma once

#include <string>

namespace cbtl::approach {

// Throws std::runtime_error if zlib fails (out of memory).
std::string gzipMember(const std::string& text);

}  // namespace cbtl::approach

// InputFile.h — reading a whole file a person named on the command line (a program, a profile, an observation, a
// solution, a profile to import), bounded: what is not a regular file (a directory, a FIFO that would block for
// ever, /dev/zero that never ends) and what is larger than the limit for its kind is refused with a message that
// names the path, before more than the limit is held in memory.
//
// The limits are generous for any real input (the largest domain program is under 40 KB; a profile of 200,000
// labels about 10 MB) and small enough that parsing one cannot exhaust a machine's memory.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

namespace cbtl::support {

inline constexpr std::uintmax_t kMiB = std::uintmax_t{1} << 20;
// A `.cbtl` source file (each file of a program: its imports too). The compiler holds ~200 bytes per source byte
// at its peak, so 4 MiB of source stays under 1 GB.
inline constexpr std::uintmax_t kMaxSourceBytes = 4 * kMiB;
// A constraint graph emitted as JSON (`cbtlc emit --format json`).
inline constexpr std::uintmax_t kMaxGraphBytes = 64 * kMiB;
// JSON data: profiles, observations, solutions, profile imports, sweep and study configurations.
inline constexpr std::uintmax_t kMaxDataBytes = 256 * kMiB;

// What went wrong, and the message: "PATH: REASON", where `reason` names the file's role ("profile",
// "observation file") as the caller gave it.
struct InputFileError : std::runtime_error {
  enum class Kind { CannotOpen, NotRegular, TooLarge };
  InputFileError(Kind kind, const std::string& path, const std::string& reason)
      : std::runtime_error(path + ": " + reason), kind(kind), reason(reason) {}
  Kind kind;
  std::string reason;  // "cannot read the profile (No such file or directory)", "not a regular file (a pipe), ..."
};

// The file's bytes. Throws InputFileError when it cannot be opened (missing, no permission), is not a regular file,
// or holds more than `maxBytes` bytes (also when it grows past them while being read).
std::string readInputFile(const std::string& path, std::uintmax_t maxBytes, std::string_view what);

// "4 MiB", "256 MiB", "512 KiB": a limit as the messages and docs say it.
std::string describeBytes(std::uintmax_t bytes);

}  // namespace cbtl::support

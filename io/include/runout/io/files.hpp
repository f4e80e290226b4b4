// Atomic file writes (temp file in the same folder, then rename) and small helpers.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace runout::io {

// Writes `bytes` to `path` so a reader sees either the old file or the whole new one.
// Throws IoError naming the path on failure.
void write_file_atomically(const std::string& path, std::string_view bytes);
std::string read_file(const std::string& path);  // throws IoError
// Reads a regular file of at most `max_bytes` (a FIFO, a device such as /dev/zero, a folder or
// a larger file is refused by name before a byte is read, so nothing blocks or fills memory).
std::string read_regular_file(const std::string& path, std::uintmax_t max_bytes);
// Removes the temporary files (NAME.tmp.PID) in `folder` and the folders below it left by
// runout processes that no longer run (a kill -9 between write and rename); returns how many.
int remove_stale_temporaries(const std::string& folder);
bool file_exists(const std::string& path);
void make_directories(const std::string& path);  // throws IoError

// FNV-1a 64-bit: checksums and cache keys.
std::uint64_t fnv1a64(std::string_view bytes, std::uint64_t seed = 14695981039346656037ull);

}  // namespace runout::io

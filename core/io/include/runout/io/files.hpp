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
bool file_exists(const std::string& path);
void make_directories(const std::string& path);  // throws IoError

// FNV-1a 64-bit: checksums and cache keys.
std::uint64_t fnv1a64(std::string_view bytes, std::uint64_t seed = 14695981039346656037ull);

}  // namespace runout::io

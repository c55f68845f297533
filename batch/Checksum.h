// Content checksums for output stamps: they detect a truncated, overwritten or corrupted file
// when a batch is resumed. Not cryptographic.
#pragma once

#include <cstdint>
#include <string>

namespace jawmesh {

/// 64-bit checksum of a byte string (FNV-1a over 8-byte little-endian words, tail bytes
/// zero-padded, length mixed in, final avalanche) as 16 lower-case hex digits. Deterministic on
/// every platform. Cost: about one multiply per 8 bytes.
std::string checksumHex(const std::string& bytes);

/// The same checksum of a file's contents, read in 1 MiB blocks.
/// Throws Error naming the file when it cannot be opened or read.
std::string fileChecksumHex(const std::string& path);

}  // namespace jawmesh

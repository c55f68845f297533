// The phantom's only source of randomness: splitmix64 hashes, so a generated phantom does not
// depend on the standard library or the platform.
#pragma once

#include <cstdint>

namespace jawmesh::phantom {

/// splitmix64 finaliser of x (Steele, Lea and Flood 2014).
inline std::uint64_t splitMix64(std::uint64_t x) {
    x += 0x9e3779b97f4a7c15ULL;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
    return x ^ (x >> 31);
}

/// Uniform in [-1, 1) from a hash (its top 53 bits).
inline double unitFromHash(std::uint64_t h) { return static_cast<double>(h >> 11) * (2.0 / 9007199254740992.0) - 1.0; }

}  // namespace jawmesh::phantom

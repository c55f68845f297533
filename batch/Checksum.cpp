// Implements batch/Checksum.h; what it computes, its rules and its contract are documented there.
#include "batch/Checksum.h"

#include "io/Error.h"

#include <cstdio>
#include <cstring>
#include <fstream>
#include <vector>

namespace jawmesh {
namespace {

constexpr std::uint64_t kFnvOffset = 0xcbf29ce484222325ull;
constexpr std::uint64_t kFnvPrime = 0x100000001b3ull;

/// Streaming state; blocks may have any length (a partial word is carried to the next block).
class Checksum {
public:
    void add(const char* data, std::size_t size) {
        for (std::size_t i = 0; i < size; ++i) {
            word_ |= static_cast<std::uint64_t>(static_cast<unsigned char>(data[i])) << (8 * filled_);
            if (++filled_ == 8) flushWord();
        }
        length_ += size;
    }
    std::string hex() {
        if (filled_ > 0) flushWord();
        std::uint64_t h = (hash_ ^ length_) * kFnvPrime;
        // Avalanche (splitmix64 finaliser) so that every input bit reaches every output digit.
        h ^= h >> 30;
        h *= 0xbf58476d1ce4e5b9ull;
        h ^= h >> 27;
        h *= 0x94d049bb133111ebull;
        h ^= h >> 31;
        char text[17];
        std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(h));
        return text;
    }

private:
    void flushWord() {
        hash_ = (hash_ ^ word_) * kFnvPrime;
        word_ = 0;
        filled_ = 0;
    }
    std::uint64_t hash_ = kFnvOffset;
    std::uint64_t word_ = 0;
    int filled_ = 0;
    std::uint64_t length_ = 0;
};

}  // namespace

std::string checksumHex(const std::string& bytes) {
    Checksum c;
    c.add(bytes.data(), bytes.size());
    return c.hex();
}

std::string fileChecksumHex(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(path, "cannot open for reading");
    Checksum c;
    std::vector<char> block(1u << 20);
    while (in) {
        in.read(block.data(), static_cast<std::streamsize>(block.size()));
        c.add(block.data(), static_cast<std::size_t>(in.gcount()));
    }
    if (in.bad()) throw Error(path, "read failed");
    return c.hex();
}

}  // namespace jawmesh

// STL: binary and ASCII readers, the binary writer, and the vertex welding that recovers the
// connectivity STL throws away. Welding is the hot path (segmentation exports hold millions of
// triangles), so it is a parallel bucket-and-hash pass instead of one big node-based hash map.
#include "io/detail/MeshFormats.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <limits>
#include <vector>

namespace jawmesh::detail {
namespace {

// Corners are handled in fixed chunks so that every intermediate result (and thus the vertex
// numbering) is the same whatever the thread count.
constexpr std::size_t kChunk = std::size_t(1) << 15;

struct CornerKey {
    std::uint32_t bits[3];
    bool operator==(const CornerKey& o) const {
        return bits[0] == o.bits[0] && bits[1] == o.bits[1] && bits[2] == o.bits[2];
    }
};

struct BucketEntry {
    CornerKey key;
    std::uint32_t corner;
};

inline CornerKey loadCorner(const char* first, std::size_t stride, std::size_t corner) {
    CornerKey k;
    std::memcpy(k.bits, first + (corner / 3) * stride + (corner % 3) * 12, 12);
    for (std::uint32_t& b : k.bits)
        if ((b & 0x7fffffffu) == 0) b = 0;  // -0 and +0 are the same point
    return k;
}

inline bool isFinite(const CornerKey& k) {
    for (std::uint32_t b : k.bits)
        if ((b & 0x7f800000u) == 0x7f800000u) return false;
    return true;
}

inline std::uint64_t hashKey(const CornerKey& k) {
    std::uint64_t h = (std::uint64_t(k.bits[0]) << 32 | k.bits[1]) ^ (std::uint64_t(k.bits[2]) * 0x9E3779B97F4A7C15ull);
    h ^= h >> 33;
    h *= 0xff51afd7ed558ccdull;
    h ^= h >> 33;
    h *= 0xc4ceb9fe1a85ec53ull;
    h ^= h >> 33;
    return h;
}

}  // namespace

namespace {

/// The binary corners as the welding passes see them: `count` corners of `stride`-apart triangles
/// in chunks of kChunk, hashed into 2^bucketBits buckets (about 4096 corners each, at most 2^14).
struct CornerPass {
    const char* first;
    std::size_t stride, count, chunks;
    int bucketBits = 0;
    std::size_t buckets = 1;
    CornerPass(const char* f, std::size_t s, std::size_t n) : first(f), stride(s), count(n), chunks((n + kChunk - 1) / kChunk) {
        while (bucketBits < 14 && (count >> bucketBits) > 4096) ++bucketBits;
        buckets = std::size_t(1) << bucketBits;
    }
    std::size_t bucketOf(std::uint64_t h) const { return bucketBits == 0 ? std::size_t(0) : static_cast<std::size_t>(h >> (64 - bucketBits)); }
    std::size_t chunkEnd(std::size_t chunk) const { return std::min(count, (chunk + 1) * kChunk); }
    CornerKey corner(std::size_t c) const { return loadCorner(first, stride, c); }
};

/// Pass 1: per-chunk bucket histograms (counts[chunk * buckets + bucket]); throws at the first
/// non-finite corner.
std::vector<std::uint32_t> countCorners(const std::string& path, const CornerPass& cp) {
    std::vector<std::uint32_t> counts(cp.chunks * cp.buckets, 0);
    std::vector<std::size_t> firstBad(cp.chunks, cp.count);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cp.chunks, 1), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t chunk = r.begin(); chunk != r.end(); ++chunk) {
            std::uint32_t* count = counts.data() + chunk * cp.buckets;
            for (std::size_t c = chunk * kChunk; c < cp.chunkEnd(chunk); ++c) {
                const CornerKey k = cp.corner(c);
                if (!isFinite(k)) {
                    firstBad[chunk] = c;
                    break;
                }
                ++count[cp.bucketOf(hashKey(k))];
            }
        }
    });
    const std::size_t bad = *std::min_element(firstBad.begin(), firstBad.end());
    if (bad < cp.count) throw Error(path, "triangle " + std::to_string(bad / 3) + " has a NaN or infinite coordinate");
    return counts;
}

/// Turns the histograms into write offsets, bucket-major and chunk-minor (so each bucket lists its
/// corners in increasing order); returns where each bucket starts (one more than buckets).
std::vector<std::size_t> bucketOffsets(const CornerPass& cp, std::vector<std::uint32_t>& counts) {
    std::vector<std::size_t> bucketStart(cp.buckets + 1, 0);
    std::size_t offset = 0;
    for (std::size_t b = 0; b < cp.buckets; ++b) {
        bucketStart[b] = offset;
        for (std::size_t chunk = 0; chunk < cp.chunks; ++chunk) {
            std::uint32_t& n = counts[chunk * cp.buckets + b];
            const std::uint32_t here = n;
            n = static_cast<std::uint32_t>(offset);
            offset += here;
        }
    }
    bucketStart[cp.buckets] = offset;
    return bucketStart;
}

/// Pass 2: every corner scattered into its bucket.
std::vector<BucketEntry> scatterCorners(const CornerPass& cp, std::vector<std::uint32_t>& offsets) {
    std::vector<BucketEntry> entries(cp.count);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cp.chunks, 1), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t chunk = r.begin(); chunk != r.end(); ++chunk) {
            std::uint32_t* next = offsets.data() + chunk * cp.buckets;
            for (std::size_t c = chunk * kChunk; c < cp.chunkEnd(chunk); ++c) {
                const CornerKey k = cp.corner(c);
                entries[next[cp.bucketOf(hashKey(k))]++] = BucketEntry{k, static_cast<std::uint32_t>(c)};
            }
        }
    });
    return entries;
}

/// Pass 3: within each bucket (small, cache-resident), every corner mapped to the first corner
/// with the same position (open addressing).
std::vector<std::uint32_t> firstCorners(const CornerPass& cp, const std::vector<BucketEntry>& entries,
                                        const std::vector<std::size_t>& bucketStart) {
    std::vector<std::uint32_t> firstCorner(cp.count);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cp.buckets, 1), [&](const tbb::blocked_range<std::size_t>& r) {
        std::vector<std::uint32_t> table;
        for (std::size_t b = r.begin(); b != r.end(); ++b) {
            const std::size_t begin = bucketStart[b], end = bucketStart[b + 1];
            std::size_t size = 16;
            while (size < 2 * (end - begin)) size *= 2;
            table.assign(size, 0);  // entry index + 1; 0 = empty
            const std::size_t mask = size - 1;
            for (std::size_t i = begin; i < end; ++i) {
                const BucketEntry& e = entries[i];
                std::size_t slot = static_cast<std::size_t>(hashKey(e.key)) & mask;
                while (true) {
                    const std::uint32_t held = table[slot];
                    if (held == 0) {
                        table[slot] = static_cast<std::uint32_t>(i - begin + 1);
                        firstCorner[e.corner] = e.corner;
                        break;
                    }
                    const BucketEntry& other = entries[begin + held - 1];
                    if (other.key == e.key) {
                        firstCorner[e.corner] = other.corner;
                        break;
                    }
                    slot = (slot + 1) & mask;
                }
            }
        }
    });
    return firstCorner;
}

/// Pass 4: the first corners numbered in corner order (per-chunk counts, then a prefix sum) as the
/// mesh's vertices; pass 5: the triangles (a first corner never comes after those referring to it).
SurfaceMesh numberVertices(const CornerPass& cp, std::size_t triangleCount, const std::vector<std::uint32_t>& firstCorner) {
    std::vector<std::uint32_t> chunkVertexStart(cp.chunks + 1, 0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cp.chunks, 1), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t chunk = r.begin(); chunk != r.end(); ++chunk) {
            std::uint32_t n = 0;
            for (std::size_t c = chunk * kChunk; c < cp.chunkEnd(chunk); ++c) n += firstCorner[c] == c;
            chunkVertexStart[chunk + 1] = n;
        }
    });
    for (std::size_t chunk = 0; chunk < cp.chunks; ++chunk) chunkVertexStart[chunk + 1] += chunkVertexStart[chunk];
    SurfaceMesh mesh;
    mesh.vertices.resize(chunkVertexStart[cp.chunks]);
    mesh.triangles.resize(triangleCount);
    std::vector<std::uint32_t> vertexOfCorner(cp.count);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cp.chunks, 1), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t chunk = r.begin(); chunk != r.end(); ++chunk) {
            std::uint32_t id = chunkVertexStart[chunk];
            for (std::size_t c = chunk * kChunk; c < cp.chunkEnd(chunk); ++c) {
                if (firstCorner[c] != c) continue;
                const CornerKey k = cp.corner(c);
                float xyz[3];
                std::memcpy(xyz, k.bits, 12);
                mesh.vertices[id] = Vec3(xyz[0], xyz[1], xyz[2]);
                vertexOfCorner[c] = id++;
            }
        }
    });
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, triangleCount, kChunk), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t t = r.begin(); t != r.end(); ++t)
            for (std::size_t j = 0; j < 3; ++j)
                mesh.triangles[t][j] = static_cast<std::int32_t>(vertexOfCorner[firstCorner[3 * t + j]]);
    });
    return mesh;
}

}  // namespace

SurfaceMesh weldFloatCorners(const std::string& path, const char* first, std::size_t triangleCount,
                             std::size_t triangleStride) {
    if (triangleCount == 0) throw Error(path, "file holds no triangles");
    if (triangleCount * 3 > kMaxElements) throw Error(path, "more than 2^31-1 triangle corners");
    const CornerPass cp(first, triangleStride, triangleCount * 3);
    std::vector<std::uint32_t> offsets = countCorners(path, cp);
    const std::vector<std::size_t> bucketStart = bucketOffsets(cp, offsets);
    std::vector<std::uint32_t> firstCorner;
    {
        const std::vector<BucketEntry> entries = scatterCorners(cp, offsets);
        firstCorner = firstCorners(cp, entries, bucketStart);
    }
    return numberVertices(cp, triangleCount, firstCorner);
}

namespace {

SurfaceMesh readBinaryStl(const std::string& path, std::string_view data) {
    if (data.size() < 84) throw Error(path, "binary STL shorter than its 84-byte header (truncated)");
    std::uint32_t count = 0;
    std::memcpy(&count, data.data() + 80, 4);
    const std::uint64_t needed = 84ull + 50ull * count;
    if (data.size() < needed)
        throw Error(path, "binary STL header promises " + std::to_string(count) + " triangles but the file holds only " +
                              std::to_string((data.size() - 84) / 50) + " (truncated or not an STL file)");
    if (data.size() > needed)
        throw Error(path, "binary STL of " + std::to_string(count) + " triangles should be " + std::to_string(needed) +
                              " bytes but the file has " + std::to_string(data.size()) + " (corrupt or not an STL file)");
    if (count == 0) throw Error(path, "STL file holds no triangles");
    return weldFloatCorners(path, data.data() + 84 + 12, count, 50);
}

SurfaceMesh readAsciiStl(const std::string& path, std::string_view data) {
    requireText(path, data, "ASCII STL");
    std::vector<float> corners;
    LineReader lines(data);
    std::string_view line;
    enum class State { Outside, InSolid, InFacet, InLoop, LoopDone } state = State::Outside;
    int facetVertices = 0;
    auto fail = [&](const std::string& what) {
        throw Error(path, "line " + std::to_string(lines.lineNumber()) + ": " + what);
    };
    while (lines.next(line)) {
        Tokens tokens(line);
        const std::string_view keyword = tokens.next();
        if (keyword.empty()) continue;
        if (keyword == "solid") {
            if (state != State::Outside) fail("'solid' inside a solid");
            state = State::InSolid;
        } else if (keyword == "endsolid") {
            if (state != State::InSolid) fail("'endsolid' inside a facet");
            state = State::Outside;
        } else if (keyword == "facet") {
            if (state != State::InSolid) fail("'facet' outside a solid or inside another facet");
            if (tokens.next() != "normal") fail("expected 'facet normal nx ny nz'");
            state = State::InFacet;
            facetVertices = 0;
        } else if (keyword == "outer") {
            if (state != State::InFacet || tokens.next() != "loop") fail("misplaced 'outer loop'");
            state = State::InLoop;
        } else if (keyword == "vertex") {
            if (state != State::InLoop) fail("'vertex' outside 'outer loop'");
            if (++facetVertices > 3) fail("facet with more than 3 vertices");
            for (int i = 0; i < 3; ++i) {
                const std::string_view token = tokens.next();
                double v = 0;
                if (!parseDouble(token, v) || !std::isfinite(static_cast<float>(v)))
                    fail("vertex coordinate " + quoted(token) + " is not a finite number");
                corners.push_back(static_cast<float>(v));
            }
        } else if (keyword == "endloop") {
            if (state != State::InLoop) fail("misplaced 'endloop'");
            if (facetVertices != 3) fail("facet with " + std::to_string(facetVertices) + " vertices (3 needed)");
            state = State::LoopDone;
        } else if (keyword == "endfacet") {
            if (state != State::LoopDone) fail("misplaced 'endfacet'");
            state = State::InSolid;
        } else {
            fail("unexpected " + quoted(keyword) + " in an ASCII STL");
        }
    }
    if (state != State::Outside) throw Error(path, "ASCII STL ends without 'endsolid' (truncated)");
    if (corners.empty()) throw Error(path, "STL file holds no triangles");
    return weldFloatCorners(path, reinterpret_cast<const char*>(corners.data()), corners.size() / 9, 36);
}

bool startsWithSolid(std::string_view data) {
    std::size_t i = 0;
    while (i < data.size() && Tokens::isSpace(data[i])) ++i;
    return data.substr(i, 5) == "solid";
}

}  // namespace

SurfaceMesh readStl(const std::string& path, std::string_view data) {
    // "solid" opens ASCII STL, but many binary exporters put it in their header too: a file whose
    // size matches its triangle count exactly is binary.
    if (data.size() >= 84) {
        std::uint32_t count = 0;
        std::memcpy(&count, data.data() + 80, 4);
        if (84ull + 50ull * count == data.size()) return readBinaryStl(path, data);
    }
    if (startsWithSolid(data)) return readAsciiStl(path, data);
    return readBinaryStl(path, data);
}

void writeBinaryStl(const SurfaceMesh& mesh, std::ostream& out) {
    char header[80] = {};
    std::snprintf(header, sizeof header, "jawmesh binary STL, millimetres");
    out.write(header, 80);
    if (mesh.triangles.size() > std::numeric_limits<std::uint32_t>::max())
        throw Error("binary STL cannot hold more than 2^32-1 triangles");
    const auto count = static_cast<std::uint32_t>(mesh.triangles.size());
    out.write(reinterpret_cast<const char*>(&count), 4);
    std::vector<char> buffer;
    buffer.reserve(50 * 4096);
    char record[50] = {};
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
        const Tri& t = mesh.triangles[i];
        const Vec3& a = mesh.vertices[static_cast<std::size_t>(t[0])];
        const Vec3& b = mesh.vertices[static_cast<std::size_t>(t[1])];
        const Vec3& c = mesh.vertices[static_cast<std::size_t>(t[2])];
        Vec3 n = (b - a).cross(c - a);
        const double len = n.norm();
        if (len > 0) n /= len;
        const float values[12] = {float(n.x()), float(n.y()), float(n.z()), float(a.x()), float(a.y()), float(a.z()),
                                  float(b.x()), float(b.y()), float(b.z()), float(c.x()), float(c.y()), float(c.z())};
        std::memcpy(record, values, 48);
        buffer.insert(buffer.end(), record, record + 50);
        if (buffer.size() >= 50 * 4096) {
            out.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
            buffer.clear();
        }
    }
    out.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
}

}  // namespace jawmesh::detail

// Implements batch/MemoryEstimate.h; what it computes, its rules and its contract are documented there.
#include "batch/MemoryEstimate.h"

#include "io/Error.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

namespace jawmesh {
namespace {
constexpr double kBaseBytes = 150e6;
constexpr double kBytesPerSurfaceVoxel = 700.0;

/// The first number in a file (cgroup files hold one number, or "max" for no limit).
std::uint64_t readNumber(const std::string& path) {
    std::ifstream in(path);
    std::uint64_t value = 0;
    if (!(in >> value)) return 0;
    return value;
}

std::uint64_t memAvailableBytes() {
    std::ifstream in("/proc/meminfo");
    std::string key;
    std::uint64_t kib = 0;
    std::string unit;
    while (in >> key >> kib >> unit)
        if (key == "MemAvailable:") return kib * 1024u;
    return 0;
}

/// Room left under this process's cgroup memory limit, or max when there is no limit.
std::uint64_t cgroupRoomBytes() {
    std::uint64_t room = std::numeric_limits<std::uint64_t>::max();
    const std::uint64_t limitV2 = readNumber("/sys/fs/cgroup/memory.max");
    if (limitV2 > 0) room = std::min(room, limitV2 - std::min(limitV2, readNumber("/sys/fs/cgroup/memory.current")));
    const std::uint64_t limitV1 = readNumber("/sys/fs/cgroup/memory/memory.limit_in_bytes");
    if (limitV1 > 0 && limitV1 < (1ull << 60))
        room = std::min(room, limitV1 - std::min(limitV1, readNumber("/sys/fs/cgroup/memory/memory.usage_in_bytes")));
    return room;
}
}  // namespace

double surfaceAreaMm2(const SurfaceMesh& mesh) {
    double area = 0;
    for (const Tri& t : mesh.triangles) {
        const Vec3& a = mesh.vertices[static_cast<std::size_t>(t[0])];
        const Vec3& b = mesh.vertices[static_cast<std::size_t>(t[1])];
        const Vec3& c = mesh.vertices[static_cast<std::size_t>(t[2])];
        area += 0.5 * (b - a).cross(c - a).norm();
    }
    return area;
}

std::uint64_t estimateRunMemoryBytes(double inputAreaMm2, double voxelMm) {
    const double bytes = kBaseBytes + kBytesPerSurfaceVoxel * inputAreaMm2 / (voxelMm * voxelMm);
    // A voxel of 1e-9 mm gives 1e24 bytes: saturate, the conversion of a larger double is undefined.
    constexpr double kMax = 1.8e19;
    return !(bytes < kMax) ? std::numeric_limits<std::uint64_t>::max() : static_cast<std::uint64_t>(bytes);
}

namespace {
double jawAreaMm2(const JawSurfaces& surfaces) {
    double area = surfaceAreaMm2(surfaces.bone);
    for (const auto& [unn, tooth] : surfaces.teeth) area += surfaceAreaMm2(tooth);
    return area;
}

std::string gigabytes(double bytes) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f GB", bytes / 1e9);
    return text;
}
}  // namespace

std::uint64_t estimateJawMemoryBytes(const JawSurfaces& surfaces, double voxelMm) {
    return estimateRunMemoryBytes(jawAreaMm2(surfaces), voxelMm);
}

void requireMemoryFits(const JawSurfaces& surfaces, double voxelMm, std::uint64_t availableBytes, const std::string& where) {
    if (availableBytes == 0) return;
    const double area = jawAreaMm2(surfaces);
    const std::uint64_t needed = estimateRunMemoryBytes(area, voxelMm);
    if (needed <= availableBytes) return;
    char voxelText[32];
    std::snprintf(voxelText, sizeof voxelText, "%g", voxelMm);
    std::string message = std::string("at a voxel of ") + voxelText + " mm this jaw needs about " +
                          gigabytes(static_cast<double>(needed)) + " (estimate for " +
                          std::to_string(static_cast<long long>(area)) + " mm^2 of input surface) but only " +
                          gigabytes(static_cast<double>(availableBytes)) + " of memory are available";
    const double room = static_cast<double>(availableBytes) - kBaseBytes;
    if (room > 0) {
        char voxel[32];
        std::snprintf(voxel, sizeof voxel, "%.3g", std::sqrt(kBytesPerSurfaceVoxel * area / room) * 1.01);
        message += std::string("; a voxel of ") + voxel + " mm or more would fit";
    }
    throw Error(where, message);
}

std::uint64_t availableMemoryBytes() {
    const std::uint64_t available = memAvailableBytes();
    const std::uint64_t room = cgroupRoomBytes();
    if (available == 0) return room == std::numeric_limits<std::uint64_t>::max() ? 0 : room;
    return std::min(available, room);
}

}  // namespace jawmesh

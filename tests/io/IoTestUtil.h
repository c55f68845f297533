// Small shapes and helpers shared by the io tests.
#pragma once

#include "io/Error.h"
#include "io/SurfaceMesh.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

namespace jawmesh::test {

/// A closed, outward-oriented axis-aligned box from lo to hi (8 vertices, 12 triangles), mm.
inline SurfaceMesh boxMesh(const Vec3& lo, const Vec3& hi) {
    SurfaceMesh m;
    for (int i = 0; i < 8; ++i)
        m.vertices.emplace_back(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(), i & 4 ? hi.z() : lo.z());
    m.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                   {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
    return m;
}

/// Writes bytes to a file (creating folders).
inline void writeBytes(const std::filesystem::path& path, const std::string& bytes) {
    std::filesystem::create_directories(path.parent_path());
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

/// Reads a whole file.
inline std::string readBytes(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/// Expects fn to throw jawmesh::Error whose message names `file` and contains `fragment`.
inline void expectErrorNaming(const std::function<void()>& fn, const std::string& file, const std::string& fragment = "") {
    try {
        fn();
        ADD_FAILURE() << "no Error thrown (expected one naming " << file << ")";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(file), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << "expected '" << fragment << "' in: " << e.what();
    }
}

/// The same surface up to vertex numbering: every triangle of a has a triangle of b with the same
/// corner positions (within tol, same cyclic order), and the counts match.
inline ::testing::AssertionResult sameGeometry(const SurfaceMesh& a, const SurfaceMesh& b, double tol) {
    if (a.triangles.size() != b.triangles.size())
        return ::testing::AssertionFailure() << a.triangles.size() << " vs " << b.triangles.size() << " triangles";
    for (std::size_t t = 0; t < a.triangles.size(); ++t)
        for (int j = 0; j < 3; ++j) {
            const Vec3& p = a.vertices[static_cast<std::size_t>(a.triangles[t][static_cast<std::size_t>(j)])];
            const Vec3& q = b.vertices[static_cast<std::size_t>(b.triangles[t][static_cast<std::size_t>(j)])];
            if ((p - q).norm() > tol)
                return ::testing::AssertionFailure() << "triangle " << t << " corner " << j << " differs by " << (p - q).norm();
        }
    return ::testing::AssertionSuccess();
}

}  // namespace jawmesh::test

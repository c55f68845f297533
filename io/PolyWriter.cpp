// Implements io/PolyWriter.h; what it computes, its rules and its contract are documented there.
#include "io/PolyWriter.h"

#include "io/AtomicFile.h"
#include "io/Error.h"
#include "io/FileNames.h"
#include "io/MeshIO.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <set>

namespace jawmesh {

namespace {

void writeNumber(std::ostream& os, double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    os << buf;
}

}  // namespace

void writeTetgenPoly(const InterfaceComplex& complex, const std::string& path) {
    const bool smesh = endsWithIgnoringCase(path, ".smesh");
    if (!smesh && !endsWithIgnoringCase(path, ".poly")) throw Error(path, "expected a .poly or .smesh file name");
    const auto& S = complex.surface;
    if (complex.sides.size() != S.triangles.size())
        throw Error(path, "interface complex has " + std::to_string(complex.sides.size()) +
                              " label pairs for " + std::to_string(S.triangles.size()) + " triangles");
    writeFileAtomically(path, [&](std::ostream& os) {
        os << "# jawmesh interface complex: facet marker = 1024 * min(label) + max(label)\n";
        os << S.vertices.size() << " 3 0 0\n";
        for (std::size_t i = 0; i < S.vertices.size(); ++i) {
            os << i + 1;
            for (int k = 0; k < 3; ++k) {
                os << ' ';
                writeNumber(os, S.vertices[i][k]);
            }
            os << '\n';
        }
        os << S.triangles.size() << " 1\n";
        for (std::size_t t = 0; t < S.triangles.size(); ++t) {
            // The marker keeps the label pair, not its order: the normal is written pointing into
            // the lower label, so that readTetgenPoly gets the sides back.
            Tri tri = S.triangles[t];
            if (complex.sides[t][0] > complex.sides[t][1]) std::swap(tri[1], tri[2]);
            const int marker = interfaceMarker(complex.sides[t][0], complex.sides[t][1]);
            if (smesh) {
                os << "3 " << tri[0] + 1 << ' ' << tri[1] + 1 << ' ' << tri[2] + 1 << ' ' << marker << '\n';
            } else {
                os << "1 0 " << marker << "\n3 " << tri[0] + 1 << ' ' << tri[1] + 1 << ' ' << tri[2] + 1 << '\n';
            }
        }
        os << "0\n";  // holes
        os << complex.seeds.size() << '\n';
        for (std::size_t r = 0; r < complex.seeds.size(); ++r) {
            os << r + 1;
            for (int k = 0; k < 3; ++k) {
                os << ' ';
                writeNumber(os, complex.seeds[r].point[k]);
            }
            os << ' ' << complex.seeds[r].label << " -1\n";
        }
    }, false);
}

SurfaceMesh regionBoundary(const InterfaceComplex& complex, Label label) {
    SurfaceMesh out;
    std::vector<std::int32_t> remap(complex.surface.vertices.size(), -1);
    for (std::size_t t = 0; t < complex.surface.triangles.size(); ++t) {
        const auto& sides = complex.sides[t];
        if (sides[0] != label && sides[1] != label) continue;
        Tri tri = complex.surface.triangles[t];
        if (sides[0] == label) std::swap(tri[1], tri[2]);  // normal pointed into the region
        for (auto& v : tri) {
            if (remap[v] < 0) {
                remap[v] = std::int32_t(out.vertices.size());
                out.vertices.push_back(complex.surface.vertices[v]);
            }
            v = remap[v];
        }
        out.triangles.push_back(tri);
    }
    return out;
}

void writeRegionBoundaries(const InterfaceComplex& complex, const std::string& folder,
                           const std::string& ext) {
    std::set<Label> labels;
    for (const auto& s : complex.sides) {
        labels.insert(s[0]);
        labels.insert(s[1]);
    }
    labels.erase(kOutsideLabel);
    for (Label L : labels)
        writeSurface(regionBoundary(complex, L),
                     (std::filesystem::path(folder) / (labelName(L) + "." + ext)).string());
}

}  // namespace jawmesh

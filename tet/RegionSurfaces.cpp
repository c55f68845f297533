// Implements tet/RegionSurfaces.h; what it computes, its rules and its contract are documented there.
#include "tet/RegionSurfaces.h"

#include "io/Error.h"
#include "io/MeshIO.h"
#include "tet/TetFaceAdjacency.h"

#include <filesystem>
#include <algorithm>

namespace jawmesh {

std::map<Label, RegionBoundary> regionBoundaries(const TetMesh& mesh) {
    const TetFaceAdjacency adj = tetFaceAdjacency(mesh);
    // Faces in adjacency order (sorted by node key), so the output is deterministic.
    std::map<Label, std::vector<Tri>> faces;
    std::map<Label, std::vector<Label>> others;
    for (std::size_t g = 0; g < adj.groupCount(); ++g) {
        const std::size_t begin = static_cast<std::size_t>(adj.groupStart[g]);
        const std::size_t size = adj.groupSize(g);
        for (std::size_t k = begin; k < begin + size; ++k) {
            const TetFaceRef& f = adj.faces[k];
            const Label own = mesh.labels[static_cast<std::size_t>(f.tet)];
            bool sameOnOtherSide = false;
            Label other = kOutsideLabel;
            for (std::size_t o = begin; o < begin + size; ++o) {
                if (o == k) continue;
                const Label l = mesh.labels[static_cast<std::size_t>(adj.faces[o].tet)];
                if (l == own) sameOnOtherSide = true;
                else if (other == kOutsideLabel) other = l;
            }
            if (sameOnOtherSide) continue;
            const auto tri = outwardFace(mesh.tets[static_cast<std::size_t>(f.tet)], f.local);
            faces[own].push_back({tri[0], tri[1], tri[2]});
            others[own].push_back(other);
        }
    }
    std::map<Label, RegionBoundary> out;
    for (auto& [label, tris] : faces) {
        out[label].otherSide = std::move(others[label]);
        out[label].surface = compactSurface(mesh.nodes, std::move(tris));
    }
    return out;
}

std::map<Label, SurfaceMesh> regionSurfaces(const TetMesh& mesh) {
    std::map<Label, SurfaceMesh> out;
    for (auto& [label, boundary] : regionBoundaries(mesh)) out[label] = std::move(boundary.surface);
    return out;
}

InterfaceComplex meshInterfaces(const TetMesh& mesh) {
    const TetFaceAdjacency adj = tetFaceAdjacency(mesh);
    InterfaceComplex c;
    std::vector<Tri> tris;
    for (std::size_t g = 0; g < adj.groupCount(); ++g) {
        if (insideOneRegion(adj, mesh, g)) continue;
        const TetFaceRef& f = adj.faces[std::size_t(adj.groupStart[g])];
        const Label in = mesh.labels[std::size_t(f.tet)];
        const Label other = adj.groupSize(g) == 2 ? mesh.labels[std::size_t(adj.faces[std::size_t(adj.groupStart[g]) + 1].tet)]
                                                  : kOutsideLabel;
        auto tri = outwardFace(mesh.tets[std::size_t(f.tet)], f.local);  // normal into `other`
        if (other > in) std::swap(tri[1], tri[2]);                        // normal into the smaller label
        tris.push_back({tri[0], tri[1], tri[2]});
        c.sides.push_back({std::min(in, other), std::max(in, other)});
    }
    c.surface = compactSurface(mesh.nodes, std::move(tris));
    return c;
}

std::string regionSurfaceFileName(Label label) {
    switch (labelKind(label)) {
    case LabelKind::Bone: return "bone.stl";
    case LabelKind::Tooth:
    case LabelKind::Pdl:
    case LabelKind::Implant: return labelName(label) + ".stl";
    default: throw Error("label " + std::to_string(label) + " has no region surface");
    }
}

std::vector<std::string> writeRegionSurfaces(const TetMesh& mesh, const std::string& folder) {
    std::vector<std::string> paths;
    const auto surfaces = regionSurfaces(mesh);
    // One jaw per output folder has one "bone.stl"; a mesh holding both bones keeps their names.
    const bool bothBones = surfaces.count(kMandibleBoneLabel) && surfaces.count(kMaxillaBoneLabel);
    for (const auto& [label, surface] : surfaces) {
        const std::string name = bothBones && labelKind(label) == LabelKind::Bone ? labelName(label) + ".stl" : regionSurfaceFileName(label);
        const std::string path = (std::filesystem::path(folder) / name).string();
        writeSurface(surface, path);
        paths.push_back(path);
    }
    return paths;
}

}  // namespace jawmesh

// Computed tooth axes against provided ones (a teeth_axes JSON), per tooth, as Markdown rows for
// docs/BENCHMARKS.md: for cases whose bone is not at hand (Open-Full-Jaw's repository keeps its
// teeth and axes in git, its bones in LFS), so the case layout's loader cannot read them.
//   bench_axes <teeth folder> <axes json> <mandible|maxilla> [bone surface]
// The teeth folder holds tooth_<UNN>.<stl|obj|ply|off>; only teeth the JSON names are compared,
// all of them are used (they shape the arch).
#include "fe/ToothAxesFromShape.h"
#include "io/Case.h"
#include "io/MeshIO.h"
#include "io/ToothAxes.h"

#include <algorithm>
#include <cstdio>
#include <exception>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

/// Every tooth_<UNN>.<ext> of a folder, by UNN, named as in the case layout.
std::map<int, jawmesh::SurfaceMesh> readTeeth(const std::string& folder, jawmesh::Jaw jaw) {
    std::map<int, jawmesh::SurfaceMesh> teeth;
    for (const auto& [unn, path] : jawmesh::toothFilesIn(folder, jaw)) teeth[unn] = jawmesh::readSurface(path);
    return teeth;
}

/// The note computed for tooth unn ("long axis from ..., mesial-distal axis from ..."), or "".
std::string noteOf(const std::vector<std::string>& notes, int unn) {
    const std::string prefix = "tooth " + std::to_string(unn) + ": ";
    std::string out;
    for (const std::string& n : notes)
        if (n.rfind(prefix, 0) == 0) out += (out.empty() ? "" : "; ") + n.substr(prefix.size());
    return out;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 4) {
        std::fprintf(stderr, "usage: bench_axes <teeth folder> <axes json> <mandible|maxilla> [bone surface]\n");
        return 2;
    }
    try {
        using namespace jawmesh;
        const Jaw jaw = std::string(argv[3]) == "maxilla" ? Jaw::Maxilla : Jaw::Mandible;
        const std::map<int, SurfaceMesh> teeth = readTeeth(argv[1], jaw);
        const std::map<int, ToothAxes> given = readToothAxes(argv[2]);
        const SurfaceMesh bone = argc > 4 ? readSurface(argv[4]) : SurfaceMesh();
        std::vector<std::string> notes;
        const std::map<int, ToothAxes> computed = toothAxesFromShape(teeth, jaw, bone, {}, &notes);
        std::printf("| tooth | long axis deg | labial axis deg | mesial-distal deg | crown centres mm | cues |\n|---|---|---|---|---|---|\n");
        double worstLong = 0, worstLabial = 0;
        int within = 0;
        for (const auto& [unn, g] : given) {
            const auto it = computed.find(unn);
            if (it == computed.end()) throw std::runtime_error("tooth " + std::to_string(unn) + " has axes but no surface");
            const ToothAxes& c = it->second;
            const double longDeg = angleDeg(c.occlusal, g.occlusal), labialDeg = angleDeg(c.labial, g.labial);
            worstLong = std::max(worstLong, longDeg), worstLabial = std::max(worstLabial, labialDeg);
            within += longDeg <= 10.0 && labialDeg <= 15.0;
            std::printf("| %d | %.1f | %.1f | %.1f | %.2f | %s |\n", unn, longDeg, labialDeg, angleDeg(c.mesialDistal, g.mesialDistal),
                        (c.crownCentre - g.crownCentre).norm(), noteOf(notes, unn).c_str());
        }
        for (const auto& [unn, c] : computed)
            if (!given.count(unn)) std::printf("| %d | no axes given | | | | %s |\n", unn, noteOf(notes, unn).c_str());
        std::printf("| worst | %.1f | %.1f | | | %d of %zu teeth within 10 deg long and 15 labial |\n", worstLong, worstLabial, within,
                    given.size());
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "bench_axes: %s\n", e.what());
        return 1;
    }
}

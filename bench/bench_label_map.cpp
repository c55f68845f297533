// bench_label_map <case> <jaw> <voxel mm> <out case> [labels.nii.gz|labels.nrrd|labels.seg.nrrd]
//                 [<PDL min mm> <PDL max mm>]:
// writes the jaw's surfaces as a label-map case (levelset/SurfacesToLabelVolume.h), to time
// `jawmesh run` on real anatomy given as labels (issue #23); with the two thicknesses, with
// segmented PDLs of uneven thickness between them (tests/support/UnevenPdl.h).
#include "io/Case.h"
#include "io/Error.h"
#include "io/LabelCase.h"
#include "levelset/JawInput.h"
#include "levelset/SurfacesToLabelVolume.h"
#include "support/UnevenPdl.h"

#include <openvdb/openvdb.h>

#include <chrono>
#include <cstdio>
#include <string>

int main(int argc, char** argv) {
    using namespace jawmesh;
    if (argc < 5 || argc == 7 || argc > 8) {
        std::fprintf(stderr, "usage: %s <case> <mandible|maxilla> <voxel mm> <out case> [labels.nii.gz] [pdl min mm, max mm]\n", argv[0]);
        return 2;
    }
    try {
        openvdb::initialize();
        const Jaw jaw = jawFromName(argv[2]);
        const auto start = std::chrono::steady_clock::now();
        for (const JawCase& jc : discoverCase(argv[1]).jaws) {
            if (jc.jaw != jaw) continue;
            const JawSurfaces surfaces = loadJawInput(jc);
            const SegmentedPdlLabels pdl = argc > 7 ? test::unevenPdlLabels(std::stod(argv[6]), std::stod(argv[7])) : SegmentedPdlLabels{};
            const LabelVolume v = labelVolumeFromSurfaces(surfaces, jc, std::stod(argv[3]), pdl);
            writeLabelCase(v, jaw, surfaces.axes, argv[4], argc > 5 ? argv[5] : "labels.nii.gz");
            std::printf("%d x %d x %d voxels, %zu labels, %.1f s\n", v.size[0], v.size[1], v.size[2], v.segments.size(),
                        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
            return 0;
        }
        throw Error(argv[1], "no " + std::string(argv[2]));
    } catch (const std::exception& e) {
        std::fprintf(stderr, "bench_label_map: %s\n", e.what());
        return 1;
    }
}

// Surfaces made a label volume with segmented PDLs (levelset/SurfacesToLabelVolume.h), the test
// data of issue #23's kept-PDL runs on real anatomy: balls of teeth in a block of bone, one in a
// socket 0.3 mm wider than its root, one overlapping the block's top. The PDL labels fill the
// socket's gap, reach the given (uneven) thickness into the bone, and stop at the bone's top (no
// PDL where the crown stands in the air).
#include "io/Labels.h"
#include "levelset/SurfacesToLabelVolume.h"
#include "support/Icosphere.h"
#include "support_meshtolevelset.h"

#include <gtest/gtest.h>

#include <openvdb/openvdb.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

namespace jawmesh {
namespace {

/// Where a voxel centre belongs for a ball of a tooth (radius rootMm) and a socket of socketMm
/// around it (0: the root overlaps the bone), below the bone's top z = 0: the PDL is the socket's
/// gap and at least thicknessMm from the root. Surely PDL, maybe (within a voxel of a wall: the
/// icospheres' facets lie up to 0.01 mm inside their spheres) or surely not.
enum class Pdl { Surely, Maybe, Not };
Pdl expectedPdl(const Vec3& p, const Vec3& centre, double rootMm, double socketMm, double thicknessMm, double voxelMm) {
    const double r = (p - centre).norm(), outer = std::max(rootMm + thicknessMm, socketMm);
    if (p.z() < -voxelMm && r > rootMm + voxelMm && r < outer - voxelMm) return Pdl::Surely;
    if (p.z() < voxelMm && r > rootMm - voxelMm && r < outer + voxelMm) return Pdl::Maybe;
    return Pdl::Not;
}

TEST(SurfacesToLabelVolume, SegmentedPdlsFillTheSocketGapAndTheirThicknessBelowTheBonesTop) {
    openvdb::initialize();
    const double voxelMm = 0.05;
    // Tooth 24: a ball of 1.5 mm in a socket of 1.8 mm, inside the block. Tooth 25: a ball of
    // 1 mm overlapping the block's top (a crown in the air above it).
    const Vec3 c24(-1.5, 0, -2.2), c25(2.2, 0, 0);
    JawSurfaces jaw;
    jaw.bone = test::boxMesh(Vec3(-4, -3, -4.5), Vec3(4, 3, 0));
    SurfaceMesh socket = test::icosphere(1.8, 4, c24);
    for (Tri& t : socket.triangles) std::swap(t[1], t[2]);  // inward: a cavity of the block
    append(jaw.bone, socket);
    jaw.teeth[24] = test::icosphere(1.5, 4, c24);
    jaw.teeth[25] = test::icosphere(1.0, 4, c25);
    JawCase jc;
    jc.folder = "balls-in-block";
    // Uneven: 0.1 mm into the bone on the -y side, 0.2 on the +y side.
    SegmentedPdlLabels pdl;
    pdl.maxThicknessMm = 0.2;
    pdl.thicknessMm = [](const Vec3& p, int) { return p.y() > 0 ? 0.2 : 0.1; };
    const LabelVolume v = labelVolumeFromSurfaces(jaw, jc, voxelMm, pdl);

    std::map<int, std::size_t> pdlVoxels, surely, misplaced;
    for (int k = 0; k < v.size[2]; ++k)
        for (int j = 0; j < v.size[1]; ++j)
            for (int i = 0; i < v.size[0]; ++i) {
                const Vec3 p = v.worldOf(i, j, k);
                const double t = p.y() > 0 ? 0.2 : 0.1;
                const std::int32_t label = v.at(0, (std::size_t(k) * v.size[1] + j) * v.size[0] + i);
                for (const auto& [unn, e] : {std::pair{24, expectedPdl(p, c24, 1.5, 1.8, t, voxelMm)},
                                             std::pair{25, expectedPdl(p, c25, 1.0, 0.0, t, voxelMm)}}) {
                    const bool isPdl = label == pdlLabel(unn);
                    pdlVoxels[unn] += isPdl;
                    surely[unn] += e == Pdl::Surely;
                    if ((isPdl && e == Pdl::Not) || (!isPdl && e == Pdl::Surely)) ++misplaced[unn];
                }
            }
    for (int unn : {24, 25}) {
        std::printf("tooth %d: PDL %zu voxels, %zu surely PDL, %zu misplaced\n", unn, pdlVoxels[unn], surely[unn], misplaced[unn]);
        EXPECT_EQ(misplaced[unn], 0u) << "tooth " << unn;
        EXPECT_GT(pdlVoxels[unn], surely[unn]) << "tooth " << unn;
    }
    EXPECT_EQ(v.segments.size(), 5u);  // bone, two teeth, two PDLs
}

}  // namespace
}  // namespace jawmesh

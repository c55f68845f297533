// Worked example of editing carved level sets (issue #3, examples/edit_levelsets/README.md):
// remove one tooth as after an extraction, leaving its socket empty, then let jawmesh continue
// from the edited grids with `jawmesh run <case> --from-vdb <edited>`.
//
// It uses OpenVDB alone, as any grid editor would; the folder's contract is in docs/DESIGN.md:
//   labels.vdb      Int32 grid, one label per voxel: 0 outside, bone, 100 + UNN tooth, 200 + UNN PDL
//   <region>.vdb    FloatGrid signed distance of one region (metadata "label"), e.g. tooth_24.vdb
// An edit must keep the two consistent: a region's voxels and its distance grid go together.
#include <openvdb/openvdb.h>
#include <openvdb/tools/Prune.h>

#include <filesystem>
#include <iostream>
#include <string>

namespace fs = std::filesystem;

int main(int argc, char** argv) {
    if (argc != 4) {
        std::cerr << "usage: remove_tooth <carved levelsets dir> <tooth UNN> <output dir>\n";
        return 2;
    }
    const fs::path in = argv[1], out = argv[3];
    const int unn = std::atoi(argv[2]);
    const int toothLabel = 100 + unn, pdlLabel = 200 + unn;
    try {
        openvdb::initialize();
        openvdb::io::File labelsFile((in / "labels.vdb").string());
        labelsFile.open();
        const openvdb::GridPtrVecPtr grids = labelsFile.getGrids();
        const openvdb::MetaMap::Ptr fileMeta = labelsFile.getMetadata();
        labelsFile.close();
        auto labels = openvdb::gridPtrCast<openvdb::Int32Grid>(grids->front());
        if (!labels) throw std::runtime_error((in / "labels.vdb").string() + ": not an Int32 label grid");

        // The tooth and its PDL become outside (0): an empty socket. Tiles (blocks of one label
        // inside a large region) are visited too, as one value each.
        openvdb::Index64 removed = 0;
        for (auto it = labels->tree().beginValueAll(); it; ++it)
            if (*it == toothLabel || *it == pdlLabel) {
                removed += it.getVoxelCount();
                it.setValue(0);
            }
        if (removed == 0) throw std::runtime_error((in / "labels.vdb").string() + ": no voxel of tooth " + argv[2]);
        openvdb::tools::prune(labels->tree());

        // Everything goes to a staging folder renamed at the end: no half-written result.
        if (fs::exists(out)) throw std::runtime_error(out.string() + ": exists already; choose a new folder");
        const fs::path stage = out.string() + ".partial";
        fs::remove_all(stage);
        fs::create_directories(stage);
        openvdb::io::File((stage / "labels.vdb").string()).write(*grids, *fileMeta);
        // The distance grids of the removed regions go; the bone's zero level already runs along
        // the socket wall (the bone side of the PDL), so the bone grid stays as it is.
        const std::string gone[2] = {"tooth_" + std::to_string(unn) + ".vdb", "pdl_" + std::to_string(unn) + ".vdb"};
        for (const auto& entry : fs::directory_iterator(in)) {
            const std::string name = entry.path().filename().string();
            if (entry.path().extension() != ".vdb" || name == "labels.vdb" || name == gone[0] || name == gone[1]) continue;
            fs::copy_file(entry.path(), stage / name);
        }
        fs::rename(stage, out);
        std::cout << "removed tooth " << unn << " and its PDL: " << removed << " voxels now outside; grids in " << out.string()
                  << "\n";
    } catch (const std::exception& e) {
        std::cerr << "remove_tooth: " << e.what() << "\n";
        return 1;
    }
    return 0;
}

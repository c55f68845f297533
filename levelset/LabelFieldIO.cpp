// Implements levelset/LabelFieldIO.h; what it computes, its rules and its contract are documented there.
#include "levelset/LabelFieldIO.h"

#include "io/AtomicFile.h"
#include "io/Error.h"
#include "levelset/VdbFile.h"

#include <openvdb/io/File.h>

#include <filesystem>
#include <set>

namespace jawmesh {
namespace {

/// An edited folder must keep labels and distance grids together: a region with voxels and no
/// distance grid would lose its sub-voxel placement, a tooth or bone grid without voxels would be a
/// region the pipeline expects and cannot find. A PDL grid without voxels is dropped: carving
/// writes one for a tooth that has no bone contact.
void requireConsistent(LabelField& field, const std::string& dir) {
    std::set<Label> present;
    Label last = kOutsideLabel;
    for (auto it = field.labels->tree().cbeginValueAll(); it; ++it)
        if (*it != last) {
            last = *it;
            present.insert(last);
        }
    present.erase(kOutsideLabel);
    for (Label L : present)
        if (!field.distances.count(L))
            throw Error(dir + "/" + labelName(L) + ".vdb",
                        "missing: labels.vdb has voxels of " + labelName(L) + " but no distance grid of it is in the folder");
    for (auto it = field.distances.begin(); it != field.distances.end();) {
        const Label L = it->first;
        if (present.count(L)) {
            ++it;
        } else if (labelKind(L) == LabelKind::Pdl) {
            it = field.distances.erase(it);
        } else {
            throw Error(dir + "/" + labelName(L) + ".vdb",
                        "labels.vdb has no voxel of " + labelName(L) + ": delete this grid, or restore its voxels");
        }
    }
}

}  // namespace

void writeLabelField(const LabelField& field, const std::string& dir) {
    if (!field.labels) throw Error(dir, "label field has no label grid");
    openvdb::initialize();
    std::filesystem::create_directories(dir);
    // Shallow copies carry the metadata so the caller's grids stay untouched.
    auto labels = field.labels->copyGrid();
    labels->setName("labels");
    labels->insertMeta("jaw", openvdb::StringMetadata(jawName(field.jaw)));
    labels->insertMeta("voxel_size_mm", openvdb::DoubleMetadata(field.voxelSizeMm));
    writeGridFile(labels, dir + "/labels.vdb");
    for (const auto& [label, grid] : field.distances) {
        if (!grid) continue;
        auto g = grid->copyGrid();
        g->setName(labelName(label));
        g->insertMeta("label", openvdb::Int32Metadata(label));
        writeGridFile(g, dir + "/" + labelName(label) + ".vdb");
    }
}

LabelField readLabelField(const std::string& dir) {
    openvdb::initialize();
    const std::string labelsPath = dir + "/labels.vdb";
    if (!std::filesystem::exists(labelsPath)) throw Error(labelsPath, "missing (not a carved label field folder)");
    LabelField field;
    field.labels = openvdb::gridPtrCast<openvdb::Int32Grid>(readGridFile(labelsPath));
    if (!field.labels) throw Error(labelsPath, "label grid is not an Int32 grid");
    if (auto jaw = field.labels->getMetadata<openvdb::StringMetadata>("jaw")) field.jaw = jawFromName(jaw->value());
    field.voxelSizeMm = field.labels->voxelSize()[0];
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
        const auto path = entry.path();
        if (path.extension() != ".vdb" || path.filename() == "labels.vdb") continue;
        auto base = readGridFile(path.string());
        auto label = base->getMetadata<openvdb::Int32Metadata>("label");
        if (!label) continue;
        auto grid = openvdb::gridPtrCast<openvdb::FloatGrid>(base);
        if (!grid) throw Error(path.string(), "region distance is not a float grid");
        if (grid->transform() != field.labels->transform())
            throw Error(path.string(), "transform differs from labels.vdb");
        labelKind(label->value());  // throws for unknown labels
        field.distances[label->value()] = grid;
    }
    requireConsistent(field, dir);
    return field;
}

}  // namespace jawmesh

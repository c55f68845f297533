// NRRD label volumes through Teem (io/LabelVolumeFormats.h): plain 3D maps and 3D Slicer's
// segmentations, whose several layers make a 4D file with a "list" axis first.
#include "io/Error.h"
#include "io/LabelVolumeFormats.h"

#include <teem/nrrd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <memory>

namespace jawmesh {
namespace {

/// Teem's accumulated error text (biff), consumed.
std::string teemError() {
    char* text = biffGetDone(NRRD);
    std::string message = text ? text : "unknown Teem error";
    std::free(text);
    while (!message.empty() && (message.back() == '\n' || message.back() == ' ')) message.pop_back();
    return message;
}

VoxelType nrrdVoxelType(int nrrdType) {
    switch (nrrdType) {
        case nrrdTypeChar: return VoxelType::Int8;
        case nrrdTypeUChar: return VoxelType::UInt8;
        case nrrdTypeShort: return VoxelType::Int16;
        case nrrdTypeUShort: return VoxelType::UInt16;
        case nrrdTypeInt: return VoxelType::Int32;
        case nrrdTypeUInt: return VoxelType::UInt32;
        default: return VoxelType::Other;
    }
}

/// Refuses lengths that are not millimetres (a unit left out is taken as millimetres).
void requireMillimetres(const Nrrd& nrrd, const std::string& path) {
    for (unsigned d = 0; d < nrrd.spaceDim; ++d) {
        const std::string unit = nrrd.spaceUnits[d] ? nrrd.spaceUnits[d] : "";
        if (unit.empty() || unit == "mm" || unit == "millimeter" || unit == "millimeters") continue;
        const std::string hint = unit == "m" || unit == "meter" || unit == "meters" ? " (metres: multiply by 1000)" : "";
        throw Error(path, "space units are '" + unit + "', not millimetres" + hint + "; write the volume in mm");
    }
}

/// Fills the voxel-to-world map from the spatial axes first..first+2.
void readGeometry(const Nrrd& nrrd, unsigned first, LabelVolume& v) {
    if (nrrd.spaceDim == 0) {
        // No space: axis spacings only (an unoriented volume), origin at 0.
        for (int a = 0; a < 3; ++a) {
            const double s = nrrd.axis[first + static_cast<unsigned>(a)].spacing;
            v.directionsMm(a, a) = std::isfinite(s) && s > 0 ? s : 1.0;
        }
        return;
    }
    if (nrrd.spaceDim != 3) throw Error(v.path, "space of dimension " + std::to_string(nrrd.spaceDim) + ", not 3");
    for (int a = 0; a < 3; ++a)
        for (int d = 0; d < 3; ++d) {
            const double c = nrrd.axis[first + static_cast<unsigned>(a)].spaceDirection[d];
            if (!std::isfinite(c)) throw Error(v.path, "axis " + std::to_string(first + static_cast<unsigned>(a)) + " has no space direction");
            v.directionsMm(d, a) = c;
        }
    for (int d = 0; d < 3; ++d) v.originMm[d] = std::isfinite(nrrd.spaceOrigin[d]) ? nrrd.spaceOrigin[d] : 0.0;
}

/// Refuses a header that declares far more data than its files hold (gzip inflates at most about
/// 1032 times) before Teem allocates it: a corrupt size must not exhaust the memory.
void requirePlausibleSize(const std::string& path) {
    namespace fs = std::filesystem;
    std::unique_ptr<Nrrd, Nrrd* (*)(Nrrd*)> header(nrrdNew(), nrrdNuke);
    std::unique_ptr<NrrdIoState, NrrdIoState* (*)(NrrdIoState*)> io(nrrdIoStateNew(), nrrdIoStateNix);
    io->skipData = AIR_TRUE;
    if (nrrdLoad(header.get(), path.c_str(), io.get())) throw Error(path, "cannot read as NRRD: " + teemError());
    double available = static_cast<double>(fs::file_size(path));
    for (unsigned i = 0; io->dataFNArr && i < io->dataFNArr->len; ++i) {
        fs::path data(io->dataFN[i]);
        if (data.is_relative()) data = fs::path(path).parent_path() / data;
        std::error_code ec;
        const auto size = fs::file_size(data, ec);
        if (!ec) available += static_cast<double>(size);
    }
    const double declared = static_cast<double>(nrrdElementSize(header.get())) * static_cast<double>(nrrdElementNumber(header.get()));
    if (declared > 1100.0 * available + 65536.0)
        throw Error(path, "the header declares " + std::to_string(declared / 1e6) + " MB of data, more than its file(s) can hold");
}

}  // namespace

LabelVolume readNrrdVolume(const std::string& path, std::map<std::string, std::string>& keyValues) {
    requirePlausibleSize(path);
    std::unique_ptr<Nrrd, Nrrd* (*)(Nrrd*)> nrrd(nrrdNew(), nrrdNuke);
    if (nrrdLoad(nrrd.get(), path.c_str(), nullptr)) throw Error(path, "cannot read as NRRD: " + teemError());
    for (unsigned i = 0; i < nrrdKeyValueSize(nrrd.get()); ++i) {
        char *key = nullptr, *value = nullptr;
        nrrdKeyValueIndex(nrrd.get(), &key, &value, i);
        if (key && value) keyValues[key] = value;
        std::free(key), std::free(value);
    }
    LabelVolume v;
    v.path = path;
    unsigned first = 0;
    if (nrrd->dim == 4) {
        // A 4D volume is taken only as Slicer's layered segmentation: a list of layers first.
        const bool slicer = keyValues.count("Segment0_LabelValue") > 0;
        if (!slicer || nrrd->axis[0].kind == nrrdKindDomain || nrrd->axis[0].kind == nrrdKindSpace)
            throw Error(path, "a 4D volume that is not a 3D Slicer layered segmentation (label maps are 3D)");
        v.layers = static_cast<int>(nrrd->axis[0].size);
        first = 1;
    } else if (nrrd->dim != 3) {
        throw Error(path, "a " + std::to_string(nrrd->dim) + "D volume (label maps are 3D)");
    }
    for (int a = 0; a < 3; ++a) v.size[static_cast<std::size_t>(a)] = static_cast<int>(nrrd->axis[first + static_cast<unsigned>(a)].size);
    requireMillimetres(*nrrd, path);
    readGeometry(*nrrd, first, v);
    const std::size_t count = v.voxels() * static_cast<std::size_t>(v.layers);
    if (!convertValues(nrrd->data, nrrdVoxelType(nrrd->type), count, v.values))
        throw Error(path, std::string("values of type ") + airEnumStr(nrrdType, nrrd->type) +
                              ": labels must be integers of 8-32 bits");
    if (v.layers > 1) {
        // Slicer stores layer-fastest (the list axis first); the volume keeps one layer after another.
        std::vector<std::int32_t> byLayer(count);
        const std::size_t n = v.voxels();
        for (std::size_t voxel = 0; voxel < n; ++voxel)
            for (std::size_t layer = 0; layer < static_cast<std::size_t>(v.layers); ++layer)
                byLayer[layer * n + voxel] = v.values[voxel * static_cast<std::size_t>(v.layers) + layer];
        v.values.swap(byLayer);
    }
    return v;
}

void writeNrrdVolume(const LabelVolume& v, const std::map<std::string, std::string>& keyValues, const std::string& path) {
    const std::size_t n = v.voxels(), layers = static_cast<std::size_t>(v.layers);
    const bool fits16 = fitsUint16(v.values);
    // Teem writes from a buffer of the file's type and order (layer fastest).
    std::vector<std::uint16_t> data16;
    std::vector<std::int32_t> data32;
    for (std::size_t voxel = 0; voxel < n; ++voxel)
        for (std::size_t layer = 0; layer < layers; ++layer) {
            const std::int32_t x = v.values[layer * n + voxel];
            if (fits16) data16.push_back(static_cast<std::uint16_t>(x));
            else data32.push_back(x);
        }
    std::unique_ptr<Nrrd, Nrrd* (*)(Nrrd*)> nrrd(nrrdNew(), nrrdNix);  // Nix: the data stays ours
    const unsigned first = layers > 1 ? 1 : 0;
    std::size_t sizes[4] = {layers, 0, 0, 0};
    for (unsigned a = 0; a < 3; ++a) sizes[first + a] = static_cast<std::size_t>(v.size[a]);
    void* data = fits16 ? static_cast<void*>(data16.data()) : static_cast<void*>(data32.data());
    auto fail = [&](const std::string& what) { throw Error(path, what + ": " + teemError()); };
    if (nrrdWrap_nva(nrrd.get(), data, fits16 ? nrrdTypeUShort : nrrdTypeInt, first + 3, sizes)) fail("cannot wrap the volume");
    if (nrrdSpaceSet(nrrd.get(), nrrdSpaceLeftPosteriorSuperior)) fail("cannot set the space");
    const double origin[3] = {v.originMm.x(), v.originMm.y(), v.originMm.z()};
    if (nrrdSpaceOriginSet(nrrd.get(), origin)) fail("cannot set the origin");
    if (first) {
        nrrd->axis[0].kind = nrrdKindList;
        for (int d = 0; d < 3; ++d) nrrd->axis[0].spaceDirection[d] = AIR_NAN;
    }
    for (unsigned a = 0; a < 3; ++a) {
        nrrd->axis[first + a].kind = nrrdKindDomain;
        for (unsigned d = 0; d < 3; ++d) nrrd->axis[first + a].spaceDirection[d] = v.directionsMm(d, a);
    }
    for (unsigned d = 0; d < 3; ++d) nrrd->spaceUnits[d] = airStrdup("mm");
    for (const auto& [key, value] : keyValues)
        if (nrrdKeyValueAdd(nrrd.get(), key.c_str(), value.c_str())) fail("cannot add key " + key);
    std::unique_ptr<NrrdIoState, NrrdIoState* (*)(NrrdIoState*)> io(nrrdIoStateNew(), nrrdIoStateNix);
    io->encoding = nrrdEncodingGzip->available() ? nrrdEncodingGzip : nrrdEncodingRaw;
    if (nrrdSave(path.c_str(), nrrd.get(), io.get())) fail("cannot write NRRD");
}

}  // namespace jawmesh

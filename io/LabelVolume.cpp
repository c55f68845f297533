// Implements io/LabelVolume.h: format dispatch, checks shared by the formats, segments, and the
// atomic write (a temporary file that keeps the name's suffix, which the libraries read).
#include "io/LabelVolume.h"

#include "io/Error.h"
#include "io/FileNames.h"
#include "io/LabelVolumeFormats.h"

#include <Eigen/LU>

#include <algorithm>
#include <filesystem>
#include <limits>
#include <map>
#include <unistd.h>

namespace jawmesh {
namespace {

bool isNifti(const std::string& path) { return endsWithIgnoringCase(path, ".nii") || endsWithIgnoringCase(path, ".nii.gz"); }
bool isNrrd(const std::string& path) { return endsWithIgnoringCase(path, ".nrrd") || endsWithIgnoringCase(path, ".nhdr"); }

template <typename T>
void convertAs(const void* data, std::size_t count, std::int32_t* out) {
    const T* in = static_cast<const T*>(data);
    for (std::size_t i = 0; i < count; ++i) out[i] = static_cast<std::int32_t>(in[i]);
}

/// Slicer's segments from the header keys (Segment<N>_Name, _LabelValue, _Layer); older files
/// without label values number the segments 1, 2, ... in one layer.
std::vector<LabelSegment> slicerSegments(const std::map<std::string, std::string>& keys, const LabelVolume& v) {
    std::vector<LabelSegment> segments;
    for (int n = 0;; ++n) {
        const std::string prefix = "Segment" + std::to_string(n) + "_";
        const auto name = keys.find(prefix + "Name");
        const auto value = keys.find(prefix + "LabelValue");
        const auto layer = keys.find(prefix + "Layer");
        if (name == keys.end() && value == keys.end()) break;
        LabelSegment s;
        s.name = name == keys.end() ? "" : name->second;
        try {
            s.value = value == keys.end() ? n + 1 : std::stoi(value->second);
            s.layer = layer == keys.end() ? 0 : std::stoi(layer->second);
        } catch (const std::exception&) {
            throw Error(v.path, "segment " + std::to_string(n) + " has a label value or layer that is not a number");
        }
        if (s.layer < 0 || s.layer >= v.layers)
            throw Error(v.path, "segment " + std::to_string(n) + " ('" + s.name + "') is on layer " + std::to_string(s.layer) +
                                    " of " + std::to_string(v.layers));
        segments.push_back(s);
    }
    return segments;
}

void checkGeometry(const LabelVolume& v) {
    if (std::min({v.size[0], v.size[1], v.size[2]}) < 1) throw Error(v.path, "a volume with no voxels");
    if (!v.directionsMm.allFinite() || !v.originMm.allFinite()) throw Error(v.path, "the voxel-to-world map is not finite");
    // Spacing relative to the axes' lengths: a zero or collinear axis leaves no volume.
    const double scale = v.directionsMm.col(0).norm() * v.directionsMm.col(1).norm() * v.directionsMm.col(2).norm();
    if (!(scale > 0) || std::abs(v.directionsMm.determinant()) < 1e-6 * scale)
        throw Error(v.path, "the voxel axes are degenerate (zero spacing or two axes along one line)");
}

}  // namespace

bool convertValues(const void* data, VoxelType type, std::size_t count, std::int32_t* out) {
    switch (type) {
        case VoxelType::Int8: convertAs<std::int8_t>(data, count, out); return true;
        case VoxelType::UInt8: convertAs<std::uint8_t>(data, count, out); return true;
        case VoxelType::Int16: convertAs<std::int16_t>(data, count, out); return true;
        case VoxelType::UInt16: convertAs<std::uint16_t>(data, count, out); return true;
        case VoxelType::Int32: convertAs<std::int32_t>(data, count, out); return true;
        case VoxelType::UInt32: {
            const auto* in = static_cast<const std::uint32_t*>(data);
            for (std::size_t i = 0; i < count; ++i)
                if (in[i] > static_cast<std::uint32_t>(std::numeric_limits<std::int32_t>::max())) return false;
            convertAs<std::uint32_t>(data, count, out);
            return true;
        }
        case VoxelType::Other: return false;
    }
    return false;
}

bool convertValues(const void* data, VoxelType type, std::size_t count, std::vector<std::int32_t>& out) {
    if (type == VoxelType::Other) return false;
    out.resize(count);
    return convertValues(data, type, count, out.data());
}

bool fitsUint16(const std::vector<std::int32_t>& values) {
    return std::all_of(values.begin(), values.end(), [](std::int32_t x) { return x >= 0 && x <= 65535; });
}

std::vector<LabelSegment> valueSegments(const LabelVolume& v) {
    std::map<std::int32_t, std::size_t> counts;
    std::int32_t last = 0;
    std::size_t run = 0;  // labels come in runs: one map update per run
    for (std::size_t i = 0; i < v.voxels(); ++i) {
        const std::int32_t x = v.values[i];
        if (x == last) {
            ++run;
            continue;
        }
        counts[last] += run;
        last = x, run = 1;
    }
    counts[last] += run;
    std::vector<LabelSegment> segments;
    for (const auto& [value, count] : counts)
        if (value != 0 && count > 0) segments.push_back({0, value, "", count});
    return segments;
}

bool isLabelVolumePath(const std::string& path) { return isNrrd(path) || isNifti(path); }

LabelVolume readLabelVolume(const std::string& path) {
    if (!std::filesystem::is_regular_file(path)) throw Error(path, "no such file");
    std::map<std::string, std::string> keys;
    LabelVolume v;
    if (isNrrd(path)) v = readNrrdVolume(path, keys);
    else if (isNifti(path)) v = readNiftiVolume(path);
    else throw Error(path, "not a label volume name (.nrrd, .nhdr, .seg.nrrd, .nii, .nii.gz)");
    checkGeometry(v);
    if (v.values.size() != v.voxels() * static_cast<std::size_t>(v.layers))
        throw Error(path, "the data holds " + std::to_string(v.values.size()) + " values, the header says " +
                              std::to_string(v.voxels() * static_cast<std::size_t>(v.layers)));
    v.segments = keys.count("Segment0_Name") || keys.count("Segment0_LabelValue") ? slicerSegments(keys, v) : valueSegments(v);
    if (v.layers > 1 && keys.count("Segment0_LabelValue") == 0) throw Error(path, "layers without Slicer segment metadata");
    for (LabelSegment& s : v.segments)
        if (s.voxelCount == 0)
            for (std::size_t i = 0; i < v.voxels(); ++i) s.voxelCount += v.at(s.layer, i) == s.value;
    std::size_t labelled = 0;
    for (const LabelSegment& s : v.segments) labelled += s.voxelCount;
    if (labelled == 0) throw Error(path, "no voxel carries a label (the volume is all background)");
    return v;
}

void writeLabelVolume(const LabelVolume& volume, const std::string& path, bool slicer) {
    if (volume.values.size() != volume.voxels() * static_cast<std::size_t>(volume.layers))
        throw Error(path, "the volume's values do not match its size");
    if (slicer && !isNrrd(path)) throw Error(path, "a Slicer segmentation is written as .seg.nrrd");
    if (endsWithIgnoringCase(path, ".nhdr")) throw Error(path, "a detached header is read, not written: write .nrrd");
    std::map<std::string, std::string> keys;
    if (slicer)
        for (std::size_t n = 0; n < volume.segments.size(); ++n) {
            const LabelSegment& s = volume.segments[n];
            const std::string prefix = "Segment" + std::to_string(n) + "_";
            keys[prefix + "ID"] = "Segment_" + std::to_string(n + 1);
            keys[prefix + "Name"] = s.name;
            keys[prefix + "LabelValue"] = std::to_string(s.value);
            keys[prefix + "Layer"] = std::to_string(s.layer);
        }
    // The temporary keeps the suffix: the libraries choose the format and compression from it.
    const std::filesystem::path target(path);
    if (target.has_parent_path()) std::filesystem::create_directories(target.parent_path());
    const std::filesystem::path tmp = target.parent_path() / (".tmp-" + std::to_string(::getpid()) + "-" + target.filename().string());
    try {
        if (isNifti(path)) writeNiftiVolume(volume, tmp.string());
        else if (isNrrd(path)) writeNrrdVolume(volume, keys, tmp.string());
        else throw Error(path, "not a label volume name (.nrrd, .seg.nrrd, .nii, .nii.gz)");
        std::filesystem::rename(tmp, target);
    } catch (const Error& e) {
        std::error_code ignored;
        std::filesystem::remove(tmp, ignored);
        throw Error(path, e.reason());
    } catch (const std::exception& e) {
        std::error_code ignored;
        std::filesystem::remove(tmp, ignored);
        throw Error(path, e.what());
    }
}

}  // namespace jawmesh

// NIfTI-1 and NIfTI-2 label volumes through nifti2 (io/LabelVolumeFormats.h).
#include "io/Error.h"
#include "io/LabelVolumeFormats.h"

#include <nifti2_io.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <vector>

namespace jawmesh {
namespace {

using NiftiPtr = std::unique_ptr<nifti_image, void (*)(nifti_image*)>;

VoxelType niftiVoxelType(int datatype) {
    switch (datatype) {
        case DT_INT8: return VoxelType::Int8;
        case DT_UINT8: return VoxelType::UInt8;
        case DT_INT16: return VoxelType::Int16;
        case DT_UINT16: return VoxelType::UInt16;
        case DT_INT32: return VoxelType::Int32;
        case DT_UINT32: return VoxelType::UInt32;
        default: return VoxelType::Other;
    }
}

/// Voxel to world: the sform when set, else the qform, else the spacings (pixdim) alone.
void readGeometry(const nifti_image& nim, LabelVolume& v) {
    const nifti_dmat44* m = nim.sform_code > 0 ? &nim.sto_xyz : nim.qform_code > 0 ? &nim.qto_xyz : nullptr;
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) v.directionsMm(r, c) = m ? m->m[r][c] : (r == c ? std::abs(nim.pixdim[c + 1]) : 0.0);
        v.originMm[r] = m ? m->m[r][3] : 0.0;
    }
    if (!m)
        for (int a = 0; a < 3; ++a)
            if (!(v.directionsMm(a, a) > 0)) v.directionsMm(a, a) = 1.0;
}

/// The voxel values, read and converted a slab at a time: the library's own loading would hold the
/// file's values and their int32 copy at once (3.6 GB for a 0.1 mm jaw of 600 M voxels as uint16).
void readValues(znzFile file, nifti_image& nim, LabelVolume& v) {
    const VoxelType type = niftiVoxelType(nim.datatype);
    if (type == VoxelType::Other)
        throw Error(v.path, std::string("values of type ") + nifti_datatype_string(nim.datatype) +
                                ": labels must be integers of 8-32 bits");
    if (znzseek(file, static_cast<long>(nim.iname_offset), SEEK_SET) < 0)
        throw Error(v.path, "cannot read as NIfTI (its data is truncated)");
    constexpr std::size_t kSlabVoxels = std::size_t(1) << 24;
    const std::size_t bytesPerVoxel = static_cast<std::size_t>(nim.nbyper);
    std::vector<unsigned char> slab(std::min(kSlabVoxels, v.voxels()) * bytesPerVoxel);
    v.values.resize(v.voxels());
    for (std::size_t first = 0; first < v.voxels(); first += kSlabVoxels) {
        const std::size_t count = std::min(kSlabVoxels, v.voxels() - first);
        const int64_t bytes = static_cast<int64_t>(count * bytesPerVoxel);
        if (nifti_read_buffer(file, slab.data(), bytes, &nim) != bytes)  // swaps the bytes as the header says
            throw Error(v.path, "cannot read as NIfTI (its data is truncated)");
        if (!convertValues(slab.data(), type, count, v.values.data() + first))
            throw Error(v.path, std::string("values of type ") + nifti_datatype_string(nim.datatype) +
                                    ": labels must be integers of 8-32 bits (a uint32 value above 2^31-1)");
    }
}

}  // namespace

LabelVolume readNiftiVolume(const std::string& path) {
    nifti_set_debug_level(0);  // our message names the file; the library's would go to stderr
    {
        // The header alone first: a size its file cannot hold (gzip inflates at most about 1032
        // times) is refused before the library allocates it.
        NiftiPtr header(nifti_image_read(path.c_str(), 0), nifti_image_free);
        if (!header) throw Error(path, "cannot read as NIfTI (not a NIfTI-1/2 file)");
        const double declared = static_cast<double>(header->nvox) * static_cast<double>(header->nbyper);
        if (!(declared >= 0)) throw Error(path, "the header declares a negative number of voxels");
        if (declared > 1100.0 * static_cast<double>(std::filesystem::file_size(path)) + 65536.0)
            throw Error(path, "the header declares " + std::to_string(declared / 1e6) + " MB of data, more than its file can hold");
    }
    nifti_image* header = nullptr;
    znzFile file = nifti_image_open(path.c_str(), const_cast<char*>("rb"), &header);
    NiftiPtr nim(header, nifti_image_free);
    const std::unique_ptr<znzFile, void (*)(znzFile*)> closer(&file, [](znzFile* f) {
        if (!znz_isnull(*f)) znzclose(*f);
    });
    if (!nim || znz_isnull(file)) throw Error(path, "cannot read as NIfTI (not a NIfTI-1/2 file)");
    LabelVolume v;
    v.path = path;
    const int64_t ndim = nim->dim[0];
    for (int64_t d = 4; d <= ndim && d < 8; ++d)
        if (nim->dim[d] > 1) throw Error(path, "a " + std::to_string(ndim) + "D volume (label maps are 3D)");
    if (ndim < 3 || nim->nz < 2) throw Error(path, "a 2D image (label maps are 3D)");
    v.size = {static_cast<int>(nim->nx), static_cast<int>(nim->ny), static_cast<int>(nim->nz)};
    // The data is read for nx * ny * nz voxels: it must be the count the size check above bounded.
    if (std::min({nim->nx, nim->ny, nim->nz}) < 1 || static_cast<int64_t>(v.voxels()) != nim->nvox)
        throw Error(path, "the header's dimensions disagree with its voxel count");
    if (nim->xyz_units == NIFTI_UNITS_METER) throw Error(path, "lengths in metres (multiply by 1000): write the volume in mm");
    if (nim->xyz_units != 0 && nim->xyz_units != NIFTI_UNITS_MM)
        throw Error(path, "lengths are not millimetres (NIfTI xyz_units " + std::to_string(nim->xyz_units) + ")");
    if (nim->scl_slope != 0 && (nim->scl_slope != 1 || nim->scl_inter != 0))
        throw Error(path, "values are scaled (scl_slope/scl_inter): labels must be stored as they are");
    readGeometry(*nim, v);
    readValues(file, *nim, v);
    return v;
}

void writeNiftiVolume(const LabelVolume& v, const std::string& path) {
    if (v.layers != 1) throw Error(path, "NIfTI holds one layer; write a layered segmentation as .seg.nrrd");
    const bool fits16 = fitsUint16(v.values);
    const int64_t dims[8] = {3, v.size[0], v.size[1], v.size[2], 1, 1, 1, 1};
    NiftiPtr nim(nifti_make_new_nim(dims, fits16 ? DT_UINT16 : DT_INT32, 1), nifti_image_free);
    if (!nim) throw Error(path, "cannot make a NIfTI image");
    if (fits16) {
        auto* out = static_cast<std::uint16_t*>(nim->data);
        for (std::size_t i = 0; i < v.values.size(); ++i) out[i] = static_cast<std::uint16_t>(v.values[i]);
    } else {
        std::memcpy(nim->data, v.values.data(), v.values.size() * sizeof(std::int32_t));
    }
    nim->sform_code = NIFTI_XFORM_SCANNER_ANAT;
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c)
            nim->sto_xyz.m[r][c] = r == 3 ? (c == 3 ? 1.0 : 0.0) : c == 3 ? v.originMm[r] : v.directionsMm(r, c);
    nim->sto_ijk = nifti_dmat44_inverse(nim->sto_xyz);
    for (int a = 0; a < 3; ++a) nim->pixdim[a + 1] = v.directionsMm.col(a).norm();
    nim->dx = nim->pixdim[1], nim->dy = nim->pixdim[2], nim->dz = nim->pixdim[3];
    nim->xyz_units = NIFTI_UNITS_MM;
    nim->nifti_type = NIFTI_FTYPE_NIFTI1_1;
    nifti_set_debug_level(0);
    if (nifti_set_filenames(nim.get(), path.c_str(), 0, 1)) throw Error(path, "not a NIfTI file name (.nii, .nii.gz)");
    nifti_image_write(nim.get());
    // nifti_image_write reports nothing: read the header back to know the file is there and whole.
    NiftiPtr back(nifti_image_read(path.c_str(), 0), nifti_image_free);
    if (!back || back->nx != v.size[0] || back->ny != v.size[1] || back->nz != v.size[2])
        throw Error(path, "cannot write NIfTI");
}

}  // namespace jawmesh

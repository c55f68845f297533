// Implements levelset/VdbFile.h; what it computes, its rules and its contract are documented there.
#include "levelset/VdbFile.h"

#include "io/AtomicFile.h"
#include "io/Error.h"

#include <openvdb/io/File.h>

namespace jawmesh {

void writeGridFile(openvdb::GridBase::Ptr grid, const std::string& path) {
    writeFileAtomicallyByName(path, [&](const std::string& tmp) {
        openvdb::io::File file(tmp);
        file.write(openvdb::GridPtrVec{grid});
        file.close();
    });
}

openvdb::GridBase::Ptr readGridFile(const std::string& path) {
    try {
        openvdb::io::File file(path);
        file.open();
        auto grids = file.getGrids();
        file.close();
        if (!grids || grids->size() != 1) throw Error(path, "expected exactly one grid");
        return grids->front();
    } catch (const openvdb::Exception& e) {
        throw Error(path, std::string("cannot read OpenVDB file: ") + e.what());
    }
}

}  // namespace jawmesh

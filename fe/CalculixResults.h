// Reading CalculiX's own output back: the .dat tables written by *NODE PRINT / *EL PRINT and the
// nodal displacement blocks of the .frd, so summaries and tests use what the solver computed.
#pragma once

#include "io/SurfaceMesh.h"

#include <array>
#include <cstdint>
#include <map>
#include <string>

namespace jawmesh {

/// Values of the last time written for each set of a .dat file. Set names as CalculiX prints
/// them (upper case); node and element numbers as in the deck (1-based).
struct CalculixDat {
    double finalTime = 0;  ///< largest step time found in any table (1 when the step completed)
    std::map<std::string, std::map<std::int32_t, Vec3>> displacements;        ///< mm
    /// Per element, the largest von Mises stress over its integration points (MPa).
    std::map<std::string, std::map<std::int32_t, double>> elementVonMisesMpa;
};

/// Reads "displacements (vx,vy,vz) for set ..." and "stresses (elem, integ.pnt.,sxx,...) for set
/// ..." tables; other tables are skipped. Throws Error(path, reason) for a missing file or a table
/// row that is not numbers. Cost: one pass over the file.
CalculixDat readCalculixDat(const std::string& path);

/// Nodal displacements (mm) of the last DISP block of an ASCII .frd, by node number; `time`
/// (optional) receives that block's step time. Throws Error when the file is missing, has no DISP
/// block or a malformed record.
std::map<std::int32_t, Vec3> readCalculixFrdDisplacements(const std::string& path, double* time = nullptr);

/// von Mises equivalent of a stress tensor given as sxx, syy, szz, sxy, sxz, syz (any unit).
double vonMises(const std::array<double, 6>& s);

}  // namespace jawmesh

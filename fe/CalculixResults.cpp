// Implements fe/CalculixResults.h; what it computes, its rules and its contract are documented there.
#include "fe/CalculixResults.h"

#include "io/Error.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

namespace jawmesh {
namespace {

/// "<kind> ... for set NAME and time  0.1000000E+01" -> (NAME, time); false if not a table header.
bool tableHeader(const std::string& line, std::string& set, double& time) {
    const auto forSet = line.find(" for set ");
    const auto andTime = line.find(" and time ");
    if (forSet == std::string::npos || andTime == std::string::npos || andTime < forSet) return false;
    set = line.substr(forSet + 9, andTime - forSet - 9);
    set.erase(set.find_last_not_of(' ') + 1);
    try {
        time = std::stod(line.substr(andTime + 10));
    } catch (const std::exception&) {
        return false;
    }
    return true;
}

bool blank(const std::string& line) { return line.find_first_not_of(" \t\r") == std::string::npos; }

}  // namespace

double vonMises(const std::array<double, 6>& s) {
    const double a = s[0] - s[1], b = s[1] - s[2], c = s[2] - s[0];
    return std::sqrt(0.5 * (a * a + b * b + c * c) + 3.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]));
}

CalculixDat readCalculixDat(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw Error(path, "cannot open CalculiX .dat output (did the solver run?)");
    CalculixDat dat;
    enum class Table { None, Displacement, Stress } table = Table::None;
    std::string set, line;
    std::map<std::string, double> timeOf;  // per set and table kind: the time of the values kept
    std::size_t lineNo = 0;
    while (std::getline(in, line)) {
        ++lineNo;
        double time = 0;
        if (tableHeader(line, set, time)) {
            const bool displacement = line.find("displacements") != std::string::npos;
            const bool stress = line.find("stresses") != std::string::npos;
            table = displacement ? Table::Displacement : stress ? Table::Stress : Table::None;
            if (table == Table::None) continue;
            const std::string key = (displacement ? "u:" : "s:") + set;
            if (!timeOf.count(key) || time > timeOf[key]) {  // a later increment replaces the earlier one
                timeOf[key] = time;
                if (displacement) dat.displacements[set].clear();
                else dat.elementVonMisesMpa[set].clear();
            }
            dat.finalTime = std::max(dat.finalTime, time);
            continue;
        }
        if (blank(line) || table == Table::None) continue;
        std::istringstream row(line);
        if (table == Table::Displacement) {
            std::int32_t node = 0;
            Vec3 u;
            if (!(row >> node >> u.x() >> u.y() >> u.z()))
                throw Error(path, "line " + std::to_string(lineNo) + ": malformed displacement row");
            dat.displacements[set][node] = u;
        } else {
            std::int32_t element = 0, point = 0;
            std::array<double, 6> s{};
            if (!(row >> element >> point >> s[0] >> s[1] >> s[2] >> s[3] >> s[4] >> s[5]))
                throw Error(path, "line " + std::to_string(lineNo) + ": malformed stress row");
            double& v = dat.elementVonMisesMpa[set][element];
            v = std::max(v, vonMises(s));
        }
    }
    return dat;
}

std::map<std::int32_t, Vec3> readCalculixFrdDisplacements(const std::string& path, double* timeOut) {
    std::ifstream in(path);
    if (!in) throw Error(path, "cannot open CalculiX .frd output (did the solver run?)");
    std::map<std::int32_t, Vec3> last, current;
    bool inDisp = false, found = false;
    double stepTime = 0, lastTime = 0;
    std::string line;
    std::size_t lineNo = 0;
    while (std::getline(in, line)) {
        ++lineNo;
        // "  100CL  102 5.00000E-01 ..." opens a result block and carries its step time.
        if (line.size() > 24 && line.compare(0, 7, "  100CL") == 0) {
            try {
                stepTime = std::stod(line.substr(12, 12));
            } catch (const std::exception&) {
                throw Error(path, "line " + std::to_string(lineNo) + ": malformed result block header");
            }
        } else if (line.compare(0, 9, " -4  DISP") == 0) {
            inDisp = true;
            current.clear();
        } else if (inDisp && line.compare(0, 3, " -3") == 0) {
            inDisp = false;
            found = true;
            last.swap(current);
            lastTime = stepTime;
        } else if (inDisp && line.compare(0, 3, " -1") == 0) {
            // Fixed columns: " -1", node I10, then E12.5 values that may touch each other.
            if (line.size() < 13 + 36) throw Error(path, "line " + std::to_string(lineNo) + ": short displacement record");
            try {
                const auto node = static_cast<std::int32_t>(std::stol(line.substr(3, 10)));
                current[node] = Vec3(std::stod(line.substr(13, 12)), std::stod(line.substr(25, 12)), std::stod(line.substr(37, 12)));
            } catch (const std::exception&) {
                throw Error(path, "line " + std::to_string(lineNo) + ": malformed displacement record");
            }
        }
    }
    if (!found) throw Error(path, "no displacement block (DISP) in the .frd file");
    if (timeOut) *timeOut = lastTime;
    return last;
}

}  // namespace jawmesh

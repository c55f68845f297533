// Pi and the degree/radian conversions, one definition for every stage (options are in degrees,
// the maths in radians).
#pragma once

namespace jawmesh {

constexpr double kPi = 3.14159265358979323846;

/// Degrees to radians (written as deg * pi / 180, the order the stages have always used).
constexpr double radians(double deg) { return deg * kPi / 180.0; }

/// Radians to degrees (rad * 180 / pi).
constexpr double degrees(double rad) { return rad * 180.0 / kPi; }

}  // namespace jawmesh

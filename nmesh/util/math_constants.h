// nmesh/util/math_constants.h — the constants the geometry code shares.
#pragma once

namespace nmesh {

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr float kPiF = float(kPi);  // for float arithmetic

}  // namespace nmesh

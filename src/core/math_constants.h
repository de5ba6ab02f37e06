// Mathematical constants the library uses (std::numbers::pi is C++20; the library is C++17).
#pragma once

namespace iarap {

inline constexpr double kPi = 3.14159265358979323846;

} // namespace iarap

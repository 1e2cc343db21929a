#ifndef mpm_base_units_h
#define mpm_base_units_h

#include <cmath>

namespace MPM
{
  /**
   * One degree in radians: parameters give angles in degrees (as
   * geotechnical data do), the code works in radians. Multiply by it:
   * `phi_degrees * degree`.
   */
  constexpr double degree = M_PI / 180.;
} // namespace MPM

#endif

#include <mpm/materials/principal_stresses.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>

namespace MPM
{
  namespace MaterialModels
  {
    namespace
    {
      /// The binary exponent of @p x (x > 0), within [-1000, 1000]: read
      /// from its bits (ilogb() is a library call in the hot path).
      inline int
      clamped_exponent(const double x)
      {
        std::uint64_t bits;
        std::memcpy(&bits, &x, sizeof bits);
        const int exponent = static_cast<int>((bits >> 52) & 0x7ff) - 1023;
        return std::max(-1000, std::min(1000, exponent));
      }

      /// 2^e for e in [-1000, 1000], built from its bits.
      inline double
      power_of_two(const int e)
      {
        const std::uint64_t bits = static_cast<std::uint64_t>(e + 1023)
                                   << 52;
        double x;
        std::memcpy(&x, &bits, sizeof x);
        return x;
      }
    } // namespace


    inline DEAL_II_ALWAYS_INLINE void
    PrincipalStresses::compute_first_stage(const SymmetricTensor<2, 3> &A,
                                           FirstStage                  &st)
    {
      const double a00 = A[0][0], a11 = A[1][1], a22 = A[2][2];
      const double a01 = A[0][1], a02 = A[0][2], a12 = A[1][2];
      st.diagonal = a01 == 0. && a02 == 0. && a12 == 0.;
      if (st.diagonal)
        {
          st.diagonal_entries = {{a00, a11, a22}};
          return;
        }
      // The deviator D = A - m I, scaled by a power of two to entries of
      // order one (exactly: the scaling rounds nothing): its principal
      // values are the tensor's less m, unscaled, and working on D rather
      // than A keeps the mean stress's round-off out of the directions;
      // the scaling keeps the products below (up to the fourth power of
      // D's entries) from underflowing or overflowing whatever the units.
      const double m       = (a00 + a11 + a22) / 3.;
      const double largest = std::max({std::abs(a00 - m),
                                       std::abs(a11 - m),
                                       std::abs(a22 - m),
                                       std::abs(a01),
                                       std::abs(a02),
                                       std::abs(a12)});
      const int    exponent      = clamped_exponent(largest);
      const double inverse_scale = power_of_two(-exponent);
      const double d0 = (a00 - m) * inverse_scale,
                   d1 = (a11 - m) * inverse_scale,
                   d2 = (a22 - m) * inverse_scale;
      const double d01 = a01 * inverse_scale, d02 = a02 * inverse_scale,
                   d12 = a12 * inverse_scale;

      // D's principal values are 2 r cos(phi_k), with r^2 = J2(D) / 3 and
      // cos(3 phi) = det(D) / (2 r^3).
      const double r2 =
        (d0 * d0 + d1 * d1 + d2 * d2 + 2. * (d01 * d01 + d02 * d02 + d12 * d12)) /
        6.;
      const double r     = std::sqrt(r2);
      const double det_d = d0 * (d1 * d2 - d12 * d12) -
                           d01 * (d01 * d2 - d12 * d02) +
                           d02 * (d01 * d12 - d1 * d02);
      const double cos_3phi =
        std::max(-1., std::min(1., det_d / (2. * r2 * r)));
      // cos_3phi >= 0: the two smaller values are the closer pair, the
      // largest (phi in [0, pi/6]) is the isolated one; else the smallest
      // (psi = phi + 2 pi/3 in [5 pi/6, pi]). Near the ends the cosine is
      // flat in phi, so acos()'s lost digits do not reach s.
      st.largest_isolated = cos_3phi >= 0.;
      const double phi    = std::acos(cos_3phi) / 3.;
      st.cos_psi =
        std::cos(phi + (st.largest_isolated ? 0. : 2.0943951023931954923));
      st.s     = 2. * r * st.cos_psi;
      st.m     = m;
      st.scale = power_of_two(exponent);
      st.r     = r;
      st.d0    = d0;
      st.d1    = d1;
      st.d2    = d2;
      st.d01   = d01;
      st.d02   = d02;
      st.d12   = d12;
    }


    PrincipalStresses::PrincipalStresses(const SymmetricTensor<2, 3> &A)
    {
      compute_first_stage(A, stage);
      if (stage.diagonal)
        {
          values = stage.diagonal_entries;
          std::sort(values.begin(), values.end(), std::greater<double>());
          bound = 0;
          return;
        }
      // The two values other than the isolated one, cos(psi -+ 2 pi/3)
      // from cos(psi) and sin(psi) >= 0: those that lose digits where they
      // coincide.
      const double cos_psi = stage.cos_psi;
      const double sin_psi = std::sqrt(std::max(0., 1. - cos_psi * cos_psi));
      const double half_root_3 = 0.86602540378443864676;
      const double two_r_scale = 2. * stage.r * stage.scale;
      const double upper       = half_root_3 * sin_psi - 0.5 * cos_psi;
      const double lower       = -half_root_3 * sin_psi - 0.5 * cos_psi;
      const double m           = stage.m;
      if (stage.largest_isolated)
        values = {{m + two_r_scale * cos_psi,
                   m + two_r_scale * upper,
                   m + two_r_scale * lower}};
      else
        values = {{m + two_r_scale * upper,
                   m + two_r_scale * lower,
                   m + two_r_scale * cos_psi}};
      bound = 1e-6 * (std::abs(m) + two_r_scale);
    }


    inline DEAL_II_ALWAYS_INLINE std::array<std::pair<double, Tensor<1, 3>>, 3>
    PrincipalStresses::second_stage(const FirstStage &st)
    {
      // (Value-initialised: zero values and directions.)
      std::array<std::pair<double, Tensor<1, 3>>, 3> result;

      if (st.diagonal)
        {
          for (unsigned int i = 0; i < 3; ++i)
            {
              result[i].first     = st.diagonal_entries[i];
              result[i].second[i] = 1.;
            }
        }
      else
        {
          const double m = st.m, scale = st.scale, s = st.s;
          const double d0 = st.d0, d1 = st.d1, d2 = st.d2;
          const double d01 = st.d01, d02 = st.d02, d12 = st.d12;

          // Its direction: the longest cross product of two rows of D - s I.
          const double b00 = d0 - s, b11 = d1 - s, b22 = d2 - s;
          const double c01[3] = {d01 * d12 - d02 * b11,
                                 d02 * d01 - b00 * d12,
                                 b00 * b11 - d01 * d01};
          const double c02[3] = {d01 * b22 - d02 * d12,
                                 d02 * d02 - b00 * b22,
                                 b00 * d12 - d01 * d02};
          const double c12[3] = {b11 * b22 - d12 * d12,
                                 d12 * d02 - d01 * b22,
                                 d01 * d12 - b11 * d02};
          const double n01 = c01[0] * c01[0] + c01[1] * c01[1] + c01[2] * c01[2];
          const double n02 = c02[0] * c02[0] + c02[1] * c02[1] + c02[2] * c02[2];
          const double n12 = c12[0] * c12[0] + c12[1] * c12[1] + c12[2] * c12[2];
          const double *c = c01;
          double        n = n01;
          if (n02 > n)
            {
              c = c02;
              n = n02;
            }
          if (n12 > n)
            {
              c = c12;
              n = n12;
            }
          const double inverse_length = 1. / std::sqrt(n);
          const double v[3]           = {c[0] * inverse_length,
                                         c[1] * inverse_length,
                                         c[2] * inverse_length};

          // An orthonormal pair u, w in the plane normal to v: u normal to v
          // and to the axis along which v is shortest.
          double       u[3];
          const double vx = std::abs(v[0]), vy = std::abs(v[1]),
                       vz = std::abs(v[2]);
          if (vx <= vy && vx <= vz)
            {
              const double k = 1. / std::sqrt(v[1] * v[1] + v[2] * v[2]);
              u[0]           = 0.;
              u[1]           = v[2] * k;
              u[2]           = -v[1] * k;
            }
          else if (vy <= vz)
            {
              const double k = 1. / std::sqrt(v[0] * v[0] + v[2] * v[2]);
              u[0]           = -v[2] * k;
              u[1]           = 0.;
              u[2]           = v[0] * k;
            }
          else
            {
              const double k = 1. / std::sqrt(v[0] * v[0] + v[1] * v[1]);
              u[0]           = v[1] * k;
              u[1]           = -v[0] * k;
              u[2]           = 0.;
            }
          const double w[3] = {v[1] * u[2] - v[2] * u[1],
                               v[2] * u[0] - v[0] * u[2],
                               v[0] * u[1] - v[1] * u[0]};

          // D in the plane: the 2 x 2 tensor [p00 p01; p01 p11] in (u, w).
          const double Du[3] = {d0 * u[0] + d01 * u[1] + d02 * u[2],
                                d01 * u[0] + d1 * u[1] + d12 * u[2],
                                d02 * u[0] + d12 * u[1] + d2 * u[2]};
          const double Dw[3] = {d0 * w[0] + d01 * w[1] + d02 * w[2],
                                d01 * w[0] + d1 * w[1] + d12 * w[2],
                                d02 * w[0] + d12 * w[1] + d2 * w[2]};
          const double p00 = u[0] * Du[0] + u[1] * Du[1] + u[2] * Du[2];
          const double p11 = w[0] * Dw[0] + w[1] * Dw[1] + w[2] * Dw[2];
          const double p01 = u[0] * Dw[0] + u[1] * Dw[1] + u[2] * Dw[2];

          // One Jacobi rotation (Golub and Van Loan, sym.schur2), the
          // smaller of the two angles that diagonalise it.
          double cosine = 1., sine = 0., t = 0.;
          if (p01 != 0.)
            {
              const double theta = (p11 - p00) / (2. * p01);
              t      = std::abs(theta) > 1e150 ?
                         0.5 / theta :
                         std::copysign(1., theta) /
                           (std::abs(theta) + std::sqrt(theta * theta + 1.));
              cosine = 1. / std::sqrt(1. + t * t);
              sine   = t * cosine;
            }
          result[0].first = m + scale * s;
          result[1].first = m + scale * (p00 - t * p01);
          result[2].first = m + scale * (p11 + t * p01);
          for (unsigned int i = 0; i < 3; ++i)
            {
              result[0].second[i] = v[i];
              result[1].second[i] = cosine * u[i] - sine * w[i];
              result[2].second[i] = sine * u[i] + cosine * w[i];
            }
        }

      if (result[0].first < result[1].first)
        std::swap(result[0], result[1]);
      if (result[1].first < result[2].first)
        std::swap(result[1], result[2]);
      if (result[0].first < result[1].first)
        std::swap(result[0], result[1]);
      return result;
    }


    std::array<std::pair<double, Tensor<1, 3>>, 3>
    PrincipalStresses::values_and_directions() const
    {
      return second_stage(stage);
    }


    std::array<std::pair<double, Tensor<1, 3>>, 3>
    principal_values_and_directions(const SymmetricTensor<2, 3> &A)
    {
      PrincipalStresses::FirstStage stage;
      PrincipalStresses::compute_first_stage(A, stage);
      return PrincipalStresses::second_stage(stage);
    }
  } // namespace MaterialModels
} // namespace MPM

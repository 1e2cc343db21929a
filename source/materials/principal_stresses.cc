#include <mpm/materials/principal_stresses.h>

#include <algorithm>
#include <cmath>

namespace MPM
{
  namespace MaterialModels
  {
    std::array<std::pair<double, Tensor<1, 3>>, 3>
    principal_values_and_directions(const SymmetricTensor<2, 3> &A)
    {
      const double a00 = A[0][0], a11 = A[1][1], a22 = A[2][2];
      const double a01 = A[0][1], a02 = A[0][2], a12 = A[1][2];
      std::array<std::pair<double, Tensor<1, 3>>, 3> result;

      const double off_diagonal = a01 * a01 + a02 * a02 + a12 * a12;
      if (off_diagonal == 0.)
        {
          for (unsigned int i = 0; i < 3; ++i)
            {
              result[i].first     = A[i][i];
              result[i].second    = Tensor<1, 3>();
              result[i].second[i] = 1.;
            }
        }
      else
        {
          // The deviator d = A - m I: its eigenvalues are 2 r cos(phi_k)
          // with r^2 = J2 / 3 and cos(3 phi) = det(d) / (2 r^3).
          const double m  = (a00 + a11 + a22) / 3.;
          const double d0 = a00 - m, d1 = a11 - m, d2 = a22 - m;
          const double r2 =
            (d0 * d0 + d1 * d1 + d2 * d2 + 2. * off_diagonal) / 6.;
          const double r = std::sqrt(r2);
          const double det_d = d0 * (d1 * d2 - a12 * a12) -
                               a01 * (a01 * d2 - a12 * a02) +
                               a02 * (a01 * a12 - d1 * a02);
          const double cos_3phi =
            std::max(-1., std::min(1., det_d / (2. * r2 * r)));
          // cos_3phi >= 0: the two smaller values are the closer pair, the
          // largest (phi in [0, pi/6]) is the isolated one; else the
          // smallest (phi + 2 pi/3 in [5 pi/6, pi]). Near the ends the
          // cosine is flat in phi, so acos()'s lost digits do not reach s.
          const double phi = std::acos(cos_3phi) / 3.;
          const double s =
            m + 2. * r *
                  std::cos(phi + (cos_3phi >= 0. ? 0. : 2.0943951023931954923));

          // Its direction: the longest cross product of two rows of A - s I.
          const double b00 = a00 - s, b11 = a11 - s, b22 = a22 - s;
          const double c01[3] = {a01 * a12 - a02 * b11,
                                 a02 * a01 - b00 * a12,
                                 b00 * b11 - a01 * a01};
          const double c02[3] = {a01 * b22 - a02 * a12,
                                 a02 * a02 - b00 * b22,
                                 b00 * a12 - a01 * a02};
          const double c12[3] = {b11 * b22 - a12 * a12,
                                 a12 * a02 - a01 * b22,
                                 a01 * a12 - b11 * a02};
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

          // A in the plane: the 2 x 2 tensor [p00 p01; p01 p11] in (u, w).
          const double Au[3] = {a00 * u[0] + a01 * u[1] + a02 * u[2],
                                a01 * u[0] + a11 * u[1] + a12 * u[2],
                                a02 * u[0] + a12 * u[1] + a22 * u[2]};
          const double Aw[3] = {a00 * w[0] + a01 * w[1] + a02 * w[2],
                                a01 * w[0] + a11 * w[1] + a12 * w[2],
                                a02 * w[0] + a12 * w[1] + a22 * w[2]};
          const double p00 = u[0] * Au[0] + u[1] * Au[1] + u[2] * Au[2];
          const double p11 = w[0] * Aw[0] + w[1] * Aw[1] + w[2] * Aw[2];
          const double p01 = u[0] * Aw[0] + u[1] * Aw[1] + u[2] * Aw[2];

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
          result[0].first = s;
          result[1].first = p00 - t * p01;
          result[2].first = p11 + t * p01;
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
  } // namespace MaterialModels
} // namespace MPM

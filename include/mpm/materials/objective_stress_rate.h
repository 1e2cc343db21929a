#ifndef mpm_materials_objective_stress_rate_h
#define mpm_materials_objective_stress_rate_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

namespace MPM
{
  using namespace dealii;

  /**
   * 'Materials/Objective stress rate': how the stress of a material point
   * follows the point's rotation, before its material model adds the
   * increment of the step's strain.
   *
   * The models are hypoelastic(-plastic): they integrate a stress rate.
   * Integrated component by component in the fixed x, y, z axes (the
   * material time derivative: 'none'), a stressed body that rotates keeps
   * its stress fixed in space, and a model's answer depends on the
   * observer's rotation. 'jaumann' integrates the Jaumann rate,
   * sigma' = sigma_dot - W sigma + sigma W with the spin W = (L - L^T)/2
   * of the velocity gradient L, objectively over each step by the rotation
   * of Hughes and Winget (1980):
   *
   *   sigma <- Q sigma Q^T,  Q = (I - dt W/2)^{-1} (I + dt W/2),
   *
   * which is exactly orthogonal for any step (the stress's invariants, and
   * so a yield function's value, are kept by the rotation). Half of it is
   * applied before the model's increment and half after
   * (MaterialLibrary::update_stress()), which makes the update second
   * order accurate in dt. Checked against the closed form of a
   * hypoelastic body in simple shear (Dienes 1979; tests
   * material_point_simple_shear*, doc/materials.md).
   *
   * The default is 'jaumann': it is the objective choice, and it leaves
   * the shipped scenes' validations where they were (the flume's peak
   * mean speed and the column collapse's runout move by 2e-4 and 1e-3
   * relative; doc/materials.md) for 3 % more time per step.
   *
   * The accumulated strain a point reports (the sum of its strain
   * increments) is not rotated: it is a record of the increments, not a
   * strain measure.
   */
  class ObjectiveStressRate
  {
  public:
    enum class Type
    {
      none,
      jaumann
    };

    /// 'Objective stress rate', in the subsection 'Materials' (entered by
    /// the caller).
    static void
    declare_parameters(ParameterHandler &prm);

    /// Reads it; the handler is in 'Materials'.
    void
    parse_parameters(ParameterHandler &prm);

    Type
    type() const
    {
      return rate;
    }

    /**
     * The rotation of the spin of the velocity gradient @p grad_v (dim x
     * dim; in 2D the plane strain rotation about z) over the time step
     * @p dt, in the form rotate() applies it: computed once for the two
     * half-step rotations of a stress update.
     */
    template <int dim>
    struct Rotation
    {
      /// 'none': rotate() does nothing.
      bool identity = true;
      /// 2D: cos and sin of the angle about z.
      double c = 1, s = 0;
      /// 3D: the rotation matrix, by rows (plain numbers: rotate() reads
      /// them one by one).
      double Q[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    };

    template <int dim>
    Rotation<dim>
    rotation(const Tensor<2, dim> &grad_v, const double dt) const
    {
      Rotation<dim> R;
      if (rate == Type::none)
        return R;
      R.identity = false;
      if constexpr (dim == 2)
        {
          const double a     = 0.25 * dt * (grad_v[0][1] - grad_v[1][0]);
          const double scale = 1. / (1. + a * a);
          R.c                = (1. - a * a) * scale;
          R.s                = 2. * a * scale;
        }
      else
        {
          // Q = (I - H)^{-1} (I + H) for H = dt W / 2 (the spin W =
          // (L - L^T) / 2, so H = dt (L - L^T) / 4), in closed form:
          // Q = I + 2 / (1 + |w|^2) (H + H^2) with H's axial vector w
          // (H v = w x v), where H^2 = w w^T - |w|^2 I; in scalars.
          const double f   = 0.25 * dt;
          const double h01 = f * (grad_v[0][1] - grad_v[1][0]);
          const double h02 = f * (grad_v[0][2] - grad_v[2][0]);
          const double h12 = f * (grad_v[1][2] - grad_v[2][1]);
          const double w[3]  = {-h12, h02, -h01};
          const double h2    = h01 * h01 + h02 * h02 + h12 * h12;
          const double scale = 2. / (1. + h2);
          const double H[3][3] = {{0, h01, h02}, {-h01, 0, h12}, {-h02, -h12, 0}};
          for (unsigned int i = 0; i < 3; ++i)
            for (unsigned int j = 0; j < 3; ++j)
              R.Q[i][j] =
                (i == j ? 1. : 0.) +
                scale * (H[i][j] + w[i] * w[j] - (i == j ? h2 : 0.));
        }
      return R;
    }

    /// Rotate @p stress by @p R (rotation()).
    template <int dim>
    static void
    rotate(SymmetricTensor<2, 3> &stress, const Rotation<dim> &R)
    {
      if (R.identity)
        return;
      apply(stress,
            R,
            [&stress](const unsigned int i,
                      const unsigned int j,
                      const double       value) { stress[i][j] = value; });
    }

    /**
     * rotate() of @p stress with its result stored at @p stored, six
     * numbers in SymmetricTensor's order (as a material point keeps its
     * stress), entry by entry; with 'none' a copy.
     *
     * Why not rotate() and a copy of the tensor: the rotation's results
     * are scalars, and written one by one into the tensor they cannot be
     * forwarded to the 16-byte loads the compiler makes of a six-number
     * copy; in 2D that stall was a fifth of PointUpdate::update_stress()'s
     * samples on the throughput block (doc/performance.md).
     */
    template <int dim>
    static void
    rotate_and_store(const SymmetricTensor<2, 3> &stress,
                     const Rotation<dim>         &R,
                     double                      *stored)
    {
      if (R.identity)
        {
          for (unsigned int k = 0; k < 6; ++k)
            stored[k] = stress.access_raw_entry(k);
          return;
        }
      apply(stress,
            R,
            [stored](const unsigned int i,
                     const unsigned int j,
                     const double       value) {
              stored[SymmetricTensor<2, 3>::component_to_unrolled_index(
                TableIndices<2>(i, j))] = value;
            });
      // (The plane strain rotation is about z.)
      if constexpr (dim == 2)
        stored[2] = stress[2][2];
    }

    /**
     * Rotate @p stress with the spin of the velocity gradient @p grad_v
     * over the time step @p dt: rotate(stress, rotation(grad_v, dt)).
     * Nothing with 'none'.
     */
    template <int dim>
    void
    rotate(SymmetricTensor<2, 3> &stress,
           const Tensor<2, dim>  &grad_v,
           const double           dt) const
    {
      rotate<dim>(stress, rotation<dim>(grad_v, dt));
    }

  private:
    /**
     * Q sigma Q^T of @p stress for the rotation @p R (not the identity),
     * each new entry (i, j), i <= j, handed to @p store(i, j, value) once
     * every entry of @p stress has been read (so @p store may write into
     * @p stress). In 2D the rotation about z leaves sigma_zz, which is not
     * handed on.
     */
    template <int dim, typename Store>
    static void
    apply(const SymmetricTensor<2, 3> &stress,
          const Rotation<dim>         &R,
          const Store                 &store)
    {
      if constexpr (dim == 2)
        {
          const double c = R.c, s = R.s;
          const double xx = stress[0][0], yy = stress[1][1],
                       xy = stress[0][1];
          const double xz = stress[0][2], yz = stress[1][2];
          const double cc = c * c, ss = s * s, cs = c * s;
          store(0, 0, cc * xx + 2. * cs * xy + ss * yy);
          store(1, 1, ss * xx - 2. * cs * xy + cc * yy);
          store(0, 1, cs * (yy - xx) + (cc - ss) * xy);
          store(0, 2, c * xz + s * yz);
          store(1, 2, -s * xz + c * yz);
        }
      else
        {
          // Q sigma Q^T for symmetric sigma: A = Q sigma, then only the
          // upper triangle of A Q^T (45 products instead of 54 and the
          // symmetrisation of a full product), entry by entry.
          const auto  &Q = R.Q;
          const double s[3][3] = {{stress[0][0], stress[0][1], stress[0][2]},
                                  {stress[0][1], stress[1][1], stress[1][2]},
                                  {stress[0][2], stress[1][2], stress[2][2]}};
          double       a[3][3];
          for (unsigned int i = 0; i < 3; ++i)
            for (unsigned int k = 0; k < 3; ++k)
              a[i][k] = Q[i][0] * s[0][k] + Q[i][1] * s[1][k] + Q[i][2] * s[2][k];
          for (unsigned int i = 0; i < 3; ++i)
            for (unsigned int j = i; j < 3; ++j)
              store(i,
                    j,
                    a[i][0] * Q[j][0] + a[i][1] * Q[j][1] + a[i][2] * Q[j][2]);
        }
    }

    Type rate = Type::none;
  };
} // namespace MPM

#endif

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
      /// 3D: the rotation matrix.
      Tensor<2, 3> Q;
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
          Tensor<2, 3> H;
          for (unsigned int i = 0; i < 3; ++i)
            for (unsigned int j = 0; j < 3; ++j)
              H[i][j] = 0.25 * dt * (grad_v[i][j] - grad_v[j][i]);
          const double h2 = H[0][1] * H[0][1] + H[0][2] * H[0][2] +
                            H[1][2] * H[1][2];
          R.Q = (2. / (1. + h2)) * (H + H * H);
          for (unsigned int i = 0; i < 3; ++i)
            R.Q[i][i] += 1.;
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
      if constexpr (dim == 2)
        {
          const double c = R.c, s = R.s;
          const double xx = stress[0][0], yy = stress[1][1],
                       xy = stress[0][1];
          const double cc = c * c, ss = s * s, cs = c * s;
          stress[0][0] = cc * xx + 2. * cs * xy + ss * yy;
          stress[1][1] = ss * xx - 2. * cs * xy + cc * yy;
          stress[0][1] = cs * (yy - xx) + (cc - ss) * xy;
          const double xz = stress[0][2], yz = stress[1][2];
          stress[0][2] = c * xz + s * yz;
          stress[1][2] = -s * xz + c * yz;
        }
      else
        {
          const Tensor<2, 3> sigma   = stress;
          const Tensor<2, 3> rotated = R.Q * sigma * transpose(R.Q);
          for (unsigned int i = 0; i < 3; ++i)
            for (unsigned int j = i; j < 3; ++j)
              stress[i][j] = 0.5 * (rotated[i][j] + rotated[j][i]);
        }
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
    Type rate = Type::none;
  };
} // namespace MPM

#endif

#ifndef mpm_materials_principal_stresses_h
#define mpm_materials_principal_stresses_h

#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <array>
#include <utility>

namespace MPM
{
  namespace MaterialModels
  {
    using namespace dealii;

    /**
     * The principal values and directions of a symmetric 3 x 3 tensor
     * (a 3D stress), in descending order of the values, as deal.II's
     * eigenvectors() returns them: what a return mapping in principal
     * stress space needs (MohrCoulomb's general 3D stress).
     *
     * Why not deal.II's eigenvectors(): its QL iteration with implicit
     * shifts took 350 ns per tensor here, most of a 3D Mohr-Coulomb update
     * of a yielding point, and this routine takes 150 ns with the same
     * accuracy (unit test principal_stresses: the residual |A v - s v|,
     * the orthonormality of the directions and the reconstruction
     * sum_i s_i v_i v_i^T within a few machine epsilons of |A|, as QL's, on
     * random tensors and on tensors with two equal or nearly equal
     * principal values, which a return to an edge of the Mohr-Coulomb
     * surface produces). Why not the closed-form eigenvalues alone
     * (deal.II's eigenvalues(), or the 'hybrid' method): where two
     * principal values coincide the trigonometric formula determines
     * those two only to the square root of the machine epsilon, and a
     * returned stress would then look slightly off the surface.
     *
     * How: on the deviator, scaled exactly by a power of two to entries
     * of order one (no underflow in the fourth powers below, whatever the
     * units; the mean stress's round-off kept out of the directions), the
     * trigonometric formula gives one principal value to full
     * accuracy, the one farthest from the middle value (the largest where
     * the two smaller ones are closer together, else the smallest): at
     * that value the formula's cosine has zero slope in the angle that
     * loses the digits. Its direction is the longest cross product of two
     * rows of D - s I (the gap to the other two values is at least half
     * the spread of all three). The other two come from the 2 x 2 tensor D
     * restricted to the plane normal to that direction, diagonalised by
     * one exact Jacobi rotation, accurate however close they are. A
     * diagonal tensor is returned as it is, with the coordinate axes.
     */
    std::array<std::pair<double, Tensor<1, 3>>, 3>
    principal_values_and_directions(const SymmetricTensor<2, 3> &A);

    /**
     * principal_values_and_directions() in two stages, for a caller that
     * may not need the second. The constructor takes the first steps of
     * that routine (the scaled deviator, the trigonometric formula's one
     * cosine) and from them all three principal values: approximate_values(),
     * within error_bound() of the accurate ones (the formula's weakness
     * where two values coincide: there they are good to about 1e-8 of the
     * deviator; error_bound() is a hundred times that, and includes the
     * mean stress's round-off). values_and_directions() then goes on to
     * the accurate decomposition, the same numbers as
     * principal_values_and_directions(A).
     *
     * Why: a decision with a margin wider than error_bound() (MohrCoulomb:
     * is the point inside every yield surface?) needs only the first
     * stage, about a third of the cost; a point that needs the directions
     * pays one square root more than with the one-stage routine.
     */
    class PrincipalStresses
    {
    public:
      explicit PrincipalStresses(const SymmetricTensor<2, 3> &A);

      /// The principal values, descending, within error_bound().
      const std::array<double, 3> &
      approximate_values() const
      {
        return values;
      }

      /// A bound on the error of approximate_values() (zero for a
      /// diagonal tensor, whose values are exact).
      double
      error_bound() const
      {
        return bound;
      }

      /// principal_values_and_directions() of the tensor.
      std::array<std::pair<double, Tensor<1, 3>>, 3>
      values_and_directions() const;

    private:
      /**
       * The first stage's numbers: the diagonal entries of a diagonal
       * tensor, else the mean m, the power of two that scales the
       * deviator, the scaled deviator's entries, r = sqrt(J2 / 3) of it,
       * the cosine of the angle of its isolated principal value and that
       * value s.
       */
      struct FirstStage
      {
        bool                  diagonal;
        std::array<double, 3> diagonal_entries;
        double m, scale, d0, d1, d2, d01, d02, d12, r, cos_psi, s;
        bool   largest_isolated;
      };
      FirstStage            stage;
      std::array<double, 3> values;
      double                bound;

      friend std::array<std::pair<double, Tensor<1, 3>>, 3>
      principal_values_and_directions(const SymmetricTensor<2, 3> &A);
      static void
      compute_first_stage(const SymmetricTensor<2, 3> &A, FirstStage &stage);
      static std::array<std::pair<double, Tensor<1, 3>>, 3>
      second_stage(const FirstStage &stage);
    };
  } // namespace MaterialModels
} // namespace MPM

#endif

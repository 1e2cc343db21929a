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
  } // namespace MaterialModels
} // namespace MPM

#endif

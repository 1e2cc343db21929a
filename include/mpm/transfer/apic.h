#ifndef mpm_transfer_apic_h
#define mpm_transfer_apic_h

#include <deal.II/base/geometry_info.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>

#include <mpm/grid/q1_shape_functions.h>
#include <mpm/transfer/transfer_scheme.h>

#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace MPM
{
  using namespace dealii;

  /**
   * 'Transfer/Scheme = apic': APIC (Jiang et al. 2015). Each point
   * carries an affine velocity field, v(x) = v_p + C_p (x - x_p), which
   * the transfers keep exactly (translation, rotation, shear), with
   * angular momentum conserved. The point update is PIC's of that field:
   * the particle-grid weights map v_p + C_p dx_i to the nodes and fit the
   * new C_p to the end-of-step grid velocity (or, under MUSL with linear
   * weights, take it from the velocity gradient of the remap), asking
   * this class for the arithmetic. doc/transfers.md has the measured
   * behaviour on linear and CPDI weights.
   *
   * The point slots (after the material state): the dim x dim matrix C_p
   * (row-major), the energy per unit mass of its affine part, and that
   * part's angular momentum per unit mass (1 component in 2D, 3 in 3D),
   * both where C_p was computed.
   */
  template <int dim>
  class Apic : public TransferScheme<dim>
  {
  public:
    static constexpr unsigned int n_vertices =
      GeometryInfo<dim>::vertices_per_cell;

    /// Reads 'Transfer/APIC energy limit'.
    explicit Apic(ParameterHandler &prm);

    unsigned int
    n_point_properties() const override
    {
      return dim * dim + 1 + n_spin_components;
    }

    std::vector<std::string>
    point_property_names() const override;

    bool
    carries_affine_velocity() const override
    {
      return true;
    }

    Tensor<1, 3>
    affine_angular_momentum_of_point(const double *slots) const override
    {
      return affine_angular_momentum(slots);
    }

    bool
    initializes_points() const override
    {
      return true;
    }

    /**
     * Complete each point's slots (its C_p, the initial velocity
     * gradient, written by the PointGenerator) with the energy and angular
     * momentum of its affine part under the first step's weights: what
     * the affine part carries (store_affine()) depends on the point's
     * second moment there.
     */
    void
    initialize_points(const ParticleGridWeights<dim> &weights,
                      const unsigned int              first_slot) const override;

    /// Components of an angular momentum: 1 in 2D (about z), 3 in 3D.
    static constexpr unsigned int n_spin_components = dim == 2 ? 1 : 3;

    /**
     * A point's second moment D_p = sum_i w_i dx_i dx_i^T of its weights
     * @p w about the nodes' offsets @p dx (dx_i = x_i - x_p).
     */
    static Tensor<2, dim>
    second_moment(const std::array<double, n_vertices>         &w,
                  const std::array<Tensor<1, dim>, n_vertices> &dx)
    {
      Tensor<2, dim> D;
      for (unsigned int i = 0; i < n_vertices; ++i)
        D += outer_product(w[i] * dx[i], dx[i]);
      return D;
    }

    /**
     * The affine matrix a point hands to the grid where its second moment
     * is @p D: its stored C_p (slots @p affine), scaled down if the
     * affine part would carry more kinetic energy here than where C_p was
     * computed.
     *
     * Why: APIC's round trip never creates energy when the point's second
     * moment D_p is the same at the grid-to-particle transfer (end of a
     * step) and at the next particle-to-grid one: the affine part's energy
     * m_p tr(C_p D_p C_p^T)/2 is then what the grid loses and gets back.
     * With quadratic B-splines D_p is a constant; with bilinear functions
     * it goes from h^2/4 at a cell's centre to 0 on its edges, so a point
     * that moves away from an edge multiplies its affine energy by
     * D_new/D_old, without bound. Measured (doc/transfers.md): without
     * this limit a freely spinning elastic body blows up within 0.3 s at
     * CFL 0.1 and within 70 steps at CFL 0.5. The limit keeps
     * m_p tr(C D_new C^T) <= m_p tr(C D_old C^T) (the energy stored in the
     * slot after C): exact wherever the point moves towards the inside of
     * its cell or stays, a small loss elsewhere. With CPDI weights D_p is
     * bounded below by the second moment of the point's domain, so the
     * ratio is bounded, but the limit still acts.
     */
    Tensor<2, dim>
    affine_matrix(const double *affine, const Tensor<2, dim> &D) const
    {
      Tensor<2, dim> C = stored_affine(affine);
      if (!limit_affine_energy)
        return C;
      const double energy = scalar_product(C * D, C);
      const double stored = affine[dim * dim];
      if (energy > stored)
        C *= std::sqrt(stored / energy);
      return C;
    }

    /// affine_matrix() at a point of a cell with linear weights (shape
    /// functions @p sf, vertex offsets @p dx).
    Tensor<2, dim>
    affine_matrix(const Q1ShapeFunctions<dim>                 &sf,
                  const std::array<Tensor<1, dim>, n_vertices> &dx,
                  const double                                 *affine) const
    {
      if (!limit_affine_energy)
        return affine_matrix(affine, Tensor<2, dim>());
      return affine_matrix(affine, second_moment(sf.value, dx));
    }

    /**
     * APIC's new affine matrix of a point from the end-of-step grid
     * velocity: C_p = B_p D_p^{-1} with B_p = sum_i w_i v_i dx_i^T and
     * D_p = sum_i w_i dx_i dx_i^T (@p B and @p D, summed by the caller
     * over the point's weights w_i, dx_i = x_i - x_p). Exact for every
     * affine grid field (linear and CPDI weights reproduce linear fields),
     * and the B D^{-1} form is what makes the round trip conserve angular
     * momentum: the points' angular momentum x_p x m_p v_p plus that of the
     * affine part, m_p skew(C_p D_p), equals the grid's
     * sum_i x_i x m_i v_i. D_p is singular where a point with linear
     * weights sits on a vertex or an edge; there (det D_p below 1e-10 of
     * @p scale^dim, the largest |dx_i|^2) the limit, the velocity gradient
     * @p gradient, is taken. Stores C_p with store_affine(); returns it.
     */
    static Tensor<2, dim>
    fit_affine(const Tensor<2, dim> &B,
               const Tensor<2, dim> &D,
               const Tensor<2, dim> &gradient,
               const double          scale,
               double               *affine)
    {
      const Tensor<2, dim> C = affine_fit(B, D, gradient, scale);
      store_affine(C, D, affine);
      return C;
    }

    /// fit_affine()'s C_p without storing it (a phase's affine transfer,
    /// PhaseKernel::needs_affine()).
    static Tensor<2, dim>
    affine_fit(const Tensor<2, dim> &B,
               const Tensor<2, dim> &D,
               const Tensor<2, dim> &gradient,
               const double          scale)
    {
      return determinant(D) > 1e-10 * std::pow(scale, dim) ?
               Tensor<2, dim>(B * invert(D)) :
               gradient;
    }

    /// fit_affine() for a point with linear weights in a cell: shape
    /// functions @p sf, vertex offsets @p dx, velocities @p v_node.
    static Tensor<2, dim>
    update_affine(const Q1ShapeFunctions<dim>                 &sf,
                  const std::array<Tensor<1, dim>, n_vertices> &dx,
                  const std::array<Tensor<1, dim>, n_vertices> &v_node,
                  double                                       *affine)
    {
      Tensor<2, dim> B, gradient;
      double         scale = 0;
      for (unsigned int i = 0; i < n_vertices; ++i)
        {
          B += outer_product(v_node[i], sf.value[i] * dx[i]);
          gradient += outer_product(v_node[i], sf.gradient[i]);
          scale = std::max(scale, dx[i].norm_square());
        }
      return fit_affine(
        B, second_moment(sf.value, dx), gradient, scale, affine);
    }

    /**
     * Store the affine matrix @p C in the point's slots @p affine, with
     * what its affine part carries where the point's second moment is
     * @p D: the energy per unit mass tr(C D C^T) (for affine_matrix())
     * and the angular momentum per unit mass, sum_i w_i dx_i x C dx_i, the
     * antisymmetric part of C D (for the conservation report).
     */
    static void
    store_affine(const Tensor<2, dim> &C,
                 const Tensor<2, dim> &D,
                 double               *affine)
    {
      for (unsigned int a = 0; a < dim; ++a)
        for (unsigned int b = 0; b < dim; ++b)
          affine[a * dim + b] = C[a][b];
      const Tensor<2, dim> CD = C * D;
      affine[dim * dim]       = trace(CD * transpose(C));
      if constexpr (dim == 2)
        affine[dim * dim + 1] = CD[1][0] - CD[0][1];
      else
        for (unsigned int a = 0; a < 3; ++a)
          {
            const unsigned int b = (a + 1) % 3, c = (a + 2) % 3;
            affine[dim * dim + 1 + a] = CD[c][b] - CD[b][c];
          }
    }

    /// The matrix C_p a point stores in its slots @p affine, as it is.
    static Tensor<2, dim>
    stored_affine(const double *affine)
    {
      Tensor<2, dim> C;
      for (unsigned int a = 0; a < dim; ++a)
        for (unsigned int b = 0; b < dim; ++b)
          C[a][b] = affine[a * dim + b];
      return C;
    }

    /// The affine part's angular momentum per unit mass stored by
    /// store_affine() (z only in 2D).
    static Tensor<1, 3>
    affine_angular_momentum(const double *affine)
    {
      Tensor<1, 3> L;
      if constexpr (dim == 2)
        L[2] = affine[dim * dim + 1];
      else
        for (unsigned int a = 0; a < 3; ++a)
          L[a] = affine[dim * dim + 1 + a];
      return L;
    }

  private:
    bool limit_affine_energy = true;
  };
} // namespace MPM

#endif

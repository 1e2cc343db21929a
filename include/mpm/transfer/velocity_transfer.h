#ifndef mpm_transfer_velocity_transfer_h
#define mpm_transfer_velocity_transfer_h

#include <deal.II/base/geometry_info.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <mpm/grid/q1_shape_functions.h>

#include <array>
#include <string>
#include <vector>

namespace MPM
{
  using namespace dealii;

  /**
   * How the point velocities reach the grid and come back: the choice that
   * decides how much kinetic energy the transfers themselves remove
   * (doc/transfers.md has the measured comparison).
   */
  enum class TransferScheme
  {
    /// v_p <- theta (v_p + dt S+ a) + (1 - theta) S+ v_L: theta = 0 is PIC
    /// (dissipative: every step keeps only the part of the point velocities
    /// that the grid represents, and smooths that), theta = 1 is FLIP (no
    /// filtering: noisy, and unstable near the limit in this code).
    flip_pic_blend,
    /// XPIC(m) (Hammerquist and Nairn 2017): PIC from a grid velocity in
    /// which the smoothing of the particle-grid-particle round trip is
    /// undone to order m. On the points no mode is amplified (see
    /// filter_coefficients()), but the filtered nodal velocity can
    /// overshoot at light nodes (a material's edge): doc/transfers.md.
    xpic,
    /// APIC (Jiang et al. 2015): each point carries an affine velocity
    /// field, v(x) = v_p + C_p (x - x_p), which the transfers keep exactly
    /// (translation, rotation, shear), with angular momentum conserved.
    apic
  };

  /**
   * The velocity transfer between material points and nodes ("Transfer"
   * in the parameter file): the scheme, its parameters and its per-point
   * arithmetic. The passes over the points that call these functions are
   * the Simulator's (one pass reads a point's data and shape functions for
   * every purpose of that pass); what differs between schemes is here.
   *
   * Every scheme leaves the nodal update alone: the nodal velocity the
   * points bring (mapped momentum / mass, with APIC's affine part, after
   * XPIC's filter) is what Coulomb friction and the wall projection act on,
   * and the points receive only the constrained end-of-step grid velocity
   * (and, with APIC, its gradient). So no scheme lets material cross a wall
   * or slide more than friction allows (doc/algorithm.md).
   */
  template <int dim>
  class VelocityTransfer
  {
  public:
    static constexpr unsigned int n_vertices =
      GeometryInfo<dim>::vertices_per_cell;

    static void
    declare_parameters(ParameterHandler &prm);

    void
    parse_parameters(ParameterHandler &prm);

    TransferScheme
    scheme() const
    {
      return transfer_scheme;
    }

    /// FLIP fraction theta of the blend (0 for XPIC and APIC, which are
    /// PIC-type updates of a better grid velocity).
    double
    flip_fraction() const
    {
      return transfer_scheme == TransferScheme::flip_pic_blend ? flip : 0.;
    }

    /// XPIC's order m (1 = PIC).
    unsigned int
    xpic_order() const
    {
      return order;
    }

    /**
     * Coefficients c_k of XPIC(m): the brought grid velocity becomes
     * u* = sum_{k=1}^m c_k (S S+)^{k-1} u, c_k = (-1)^{k+1} binomial(m, k),
     * with S+ the interpolation to the points and S the mass-weighted
     * projection back. On the points this is 1 - (1 - A)^m with
     * A = S+ S, whose eigenvalues lie in [0, 1]: the filter's lie in [0, 1]
     * too (no mode is amplified), those of the smooth modes (A near 1) move
     * much closer to 1 than PIC's A, and the null modes (noise) stay at 0.
     */
    const std::vector<double> &
    filter_coefficients() const
    {
      return xpic_coefficients;
    }

    /**
     * Property slots this scheme keeps per point, after the material
     * state (APIC: the dim x dim matrix C_p, row-major).
     */
    unsigned int
    n_point_properties() const
    {
      return transfer_scheme == TransferScheme::apic ? dim * dim + 1 : 0;
    }

    std::vector<std::string>
    point_property_names() const;

    /**
     * The affine matrix a point hands to the grid at its current position
     * (shape functions @p sf, vertex offsets @p dx): its stored C_p, scaled
     * down if the affine part would carry more kinetic energy here than
     * where C_p was computed.
     *
     * Why: APIC's round trip never creates energy when the point's second
     * moment D_p = sum_i N_i dx_i dx_i^T is the same at the grid-to-
     * particle transfer (end of a step) and at the next particle-to-grid
     * one: the affine part's energy m_p tr(C_p D_p C_p^T)/2 is then what
     * the grid loses and gets back. With quadratic B-splines D_p is a
     * constant; with bilinear functions it goes from h^2/4 at a cell's
     * centre to 0 on its edges, so a point that moves away from an edge
     * multiplies its affine energy by D_new/D_old, without bound. Measured
     * (doc/transfers.md): without this limit a freely spinning elastic
     * body blows up within 0.3 s at CFL 0.1 and within 70 steps at CFL 0.5.
     * The limit keeps m_p tr(C D_new C^T) <= m_p tr(C D_old C^T) (the
     * energy stored in the last slot): exact wherever the point moves
     * towards the inside of its cell or stays, a small loss elsewhere.
     */
    Tensor<2, dim>
    affine_matrix(const Q1ShapeFunctions<dim>                 &sf,
                  const std::array<Tensor<1, dim>, n_vertices> &dx,
                  const double                                 *affine) const
    {
      Tensor<2, dim> C;
      for (unsigned int a = 0; a < dim; ++a)
        for (unsigned int b = 0; b < dim; ++b)
          C[a][b] = affine[a * dim + b];
      if (!limit_affine_energy)
        return C;
      const double energy = affine_energy(sf, dx, C);
      const double stored = affine[dim * dim];
      if (energy > stored)
        C *= std::sqrt(stored / energy);
      return C;
    }

    /**
     * APIC's new affine matrix of a point from the end-of-step grid
     * velocity @p v_node at its cell's vertices: C_p = B_p D_p^{-1} with
     * B_p = sum_i N_i v_i dx_i^T and D_p = sum_i N_i dx_i dx_i^T
     * (dx_i = x_i - x_p). Exact for every affine grid field on any
     * isoparametric cell (the Q1 functions reproduce linear fields), and
     * the B D^{-1} form is what makes the round trip conserve angular
     * momentum: the points' angular momentum x_p x m_p v_p plus that of the
     * affine part, m_p skew(C_p D_p), equals the grid's sum_i x_i x m_i v_i.
     * D_p is singular where the point sits on a vertex or an edge; there
     * (det D_p below 1e-10 of its scale) the limit, the velocity gradient
     * sum_i v_i (x) grad N_i, is taken. Stores C_p and the energy per
     * unit mass of the affine part at this position, sum_i N_i |C dx_i|^2
     * (= tr(C D C^T)), for affine_matrix(); returns C_p.
     */
    static Tensor<2, dim>
    update_affine(const Q1ShapeFunctions<dim>                 &sf,
                  const std::array<Tensor<1, dim>, n_vertices> &dx,
                  const std::array<Tensor<1, dim>, n_vertices> &v_node,
                  double                                       *affine);

    /**
     * Store the affine matrix @p C in the point's slots @p affine, with
     * the energy per unit mass of its affine part at this position,
     * sum_i N_i |C dx_i|^2 = tr(C D_p C^T), for affine_matrix().
     */
    static void
    store_affine(const Q1ShapeFunctions<dim>                 &sf,
                 const std::array<Tensor<1, dim>, n_vertices> &dx,
                 const Tensor<2, dim>                         &C,
                 double                                       *affine)
    {
      for (unsigned int a = 0; a < dim; ++a)
        for (unsigned int b = 0; b < dim; ++b)
          affine[a * dim + b] = C[a][b];
      affine[dim * dim] = affine_energy(sf, dx, C);
    }

  private:
    /// Twice the kinetic energy per unit mass of the affine field C at a
    /// point: sum_i N_i |C dx_i|^2 = tr(C D_p C^T).
    static double
    affine_energy(const Q1ShapeFunctions<dim>                 &sf,
                  const std::array<Tensor<1, dim>, n_vertices> &dx,
                  const Tensor<2, dim>                         &C)
    {
      double energy = 0;
      for (unsigned int i = 0; i < n_vertices; ++i)
        energy += sf.value[i] * (C * dx[i]).norm_square();
      return energy;
    }

    TransferScheme transfer_scheme = TransferScheme::flip_pic_blend;
    double         flip            = 0;
    unsigned int   order           = 2;
    bool           limit_affine_energy = true;
    /// XPIC's c_k, set with the order in parse_parameters().
    std::vector<double> xpic_coefficients;
  };


  template <int dim>
  inline Tensor<2, dim>
  VelocityTransfer<dim>::update_affine(
    const Q1ShapeFunctions<dim>                 &sf,
    const std::array<Tensor<1, dim>, n_vertices> &dx,
    const std::array<Tensor<1, dim>, n_vertices> &v_node,
    double                                       *affine)
  {
    Tensor<2, dim> B, D;
    double         scale = 0;
    for (unsigned int i = 0; i < n_vertices; ++i)
      {
        const Tensor<1, dim> w_dx = sf.value[i] * dx[i];
        B += outer_product(v_node[i], w_dx);
        D += outer_product(w_dx, dx[i]);
        scale = std::max(scale, dx[i].norm_square());
      }
    Tensor<2, dim> C;
    if (determinant(D) > 1e-10 * std::pow(scale, dim))
      C = B * invert(D);
    else
      for (unsigned int i = 0; i < n_vertices; ++i)
        C += outer_product(v_node[i], sf.gradient[i]);
    store_affine(sf, dx, C, affine);
    return C;
  }
} // namespace MPM

#endif

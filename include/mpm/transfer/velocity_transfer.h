#ifndef mpm_transfer_velocity_transfer_h
#define mpm_transfer_velocity_transfer_h

#include <deal.II/base/geometry_info.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <mpm/grid/q1_shape_functions.h>

#include <array>
#include <cmath>
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

    /**
     * FLIP fraction theta of the blend for a step of length @p dt (0 for
     * XPIC and APIC, which are PIC-type updates of a better grid
     * velocity).
     *
     * Each step the blend keeps the share theta of the part of the point
     * velocities that the grid does not represent and replaces the rest by
     * the grid's (PIC's damping). With one theta per step that damping
     * per unit time grows as the time step shrinks: halving the CFL number
     * at theta = 0.98 damps like theta = 0.96 at the original step, and
     * moved the flume's final front by 1.2 cm (doc/transfers.md). With
     * 'FLIP fraction time step' dt_ref > 0, theta is the share kept per
     * dt_ref and a step keeps theta^(dt / dt_ref): the same damping per
     * unit time at every time step (the flume at CFL 0.25 then matches
     * CFL 0.5 within 2 mm).
     */
    double
    flip_fraction(const double dt) const
    {
      if (transfer_scheme != TransferScheme::flip_pic_blend)
        return 0.;
      if (flip_time_step > 0 && flip > 0 && flip < 1)
        return std::pow(flip, dt / flip_time_step);
      return flip;
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
     * state. APIC: the dim x dim matrix C_p (row-major), the energy per
     * unit mass of its affine part, and that part's angular momentum per
     * unit mass (1 component in 2D, 3 in 3D), both where C_p was computed.
     */
    unsigned int
    n_point_properties() const
    {
      return transfer_scheme == TransferScheme::apic ?
               dim * dim + 1 + n_spin_components :
               0;
    }

    std::vector<std::string>
    point_property_names() const;

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
      const Tensor<2, dim> C = determinant(D) > 1e-10 * std::pow(scale, dim) ?
                                 B * invert(D) :
                                 gradient;
      store_affine(C, D, affine);
      return C;
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
    TransferScheme transfer_scheme = TransferScheme::flip_pic_blend;
    double         flip            = 0;
    /// The time step 'FLIP fraction' refers to (0: every step).
    double         flip_time_step  = 0;
    unsigned int   order           = 2;
    bool           limit_affine_energy = true;
    /// XPIC's c_k, set with the order in parse_parameters().
    std::vector<double> xpic_coefficients;
  };


} // namespace MPM

#endif

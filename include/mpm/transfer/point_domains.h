#ifndef mpm_transfer_point_domains_h
#define mpm_transfer_point_domains_h

#include <deal.II/base/geometry_info.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <array>
#include <string>
#include <vector>

namespace MPM
{
  using namespace dealii;

  /**
   * The material points' domains for CPDI on the isoparametric mesh, and
   * the arithmetic that turns a domain into weights.
   *
   * A point's domain is a quadrilateral (hexahedron) given by the offsets
   * D_c of its 2^dim corners from the point, stored in the point's
   * properties. It starts as the point's sub-cell, the image of a
   * reference square about the point (initial_domain(): the domains tile
   * the material, and on a ground-conforming mesh those of the points next
   * to the ground lie along it), and follows the point's deformation:
   * D_c <- (I + dt grad v) D_c with the same velocity gradient that updates
   * its stress and volume (so it stays the affine image of its sub-cell).
   *
   * The weight of node i is the average of its shape function over the
   * domain, with N_i interpolated from the domain's corners x_c by the
   * domain's own multilinear functions M_c:
   *   w_i = sum_c alpha_c N_i(x_c),  grad w_i = sum_c beta_c N_i(x_c),
   *   alpha_c = (1/V) int M_c,  beta_c = (1/V) int grad M_c.
   * Whatever the corners (a corner that is moved, see below, makes the
   * domain a general quadrilateral), sum_c alpha_c = 1 and sum_c beta_c = 0,
   * so the weights are a partition of unity with gradients summing to zero,
   * and sum_c beta_c (x) x_c = I: a linear velocity field gives its exact
   * gradient. For a parallelepiped alpha_c = 2^-dim.
   *
   * A corner must lie in a cell of the mesh that a step can write to: the
   * point's own cell or one sharing a vertex with it (the same set on one
   * rank or many: every such cell is owned or a ghost). A corner outside
   * that patch (outside the mesh, beyond a wall, or a domain stretched over
   * more than a cell) makes CpdiWeights shrink the whole domain about the
   * point (x_p + s D_c, the largest s in (0, 1] found by bisection, kept
   * in the point's last slot, doubled if possible every 8th step), so it
   * stays centred on the point: a point at a wall tends to the linear
   * weights there and moves with the wall's nodes. That holds for a
   * corner just outside too (domains built from the Jacobian at a point
   * poke out of a distorted boundary cell by a little): moved onto the
   * cell instead, it would put the domain's centroid, whose velocity
   * moves the point, off the point, towards the inside, and a point next
   * to a wall would creep through it.
   */
  template <int dim>
  class PointDomains
  {
  public:
    static constexpr unsigned int n_corners =
      GeometryInfo<dim>::vertices_per_cell;

    static void
    declare_parameters(ParameterHandler &prm);

    void
    parse_parameters(ParameterHandler &prm);

    /// The offsets x_c - x_p of a domain's corners (deal.II's vertex
    /// order).
    using Offsets = std::array<Tensor<1, dim>, n_corners>;

    /// Property slots per point: the corner offsets, then
    /// the scale by which the domain is shrunk at a boundary (see the
    /// class documentation).
    unsigned int
    n_point_properties() const
    {
      return scale_slot + 1;
    }

    /// The slot of the shrink scale, after the corner offsets.
    static constexpr unsigned int scale_slot = n_corners * dim;

    std::vector<std::string>
    point_property_names() const;

    /**
     * The initial domain of a point of volume @p volume at reference
     * coordinates @p xi of the cell with @p vertices: the image through the
     * cell's map of the reference square (cube) centred at @p xi whose
     * image has the point's volume (to the accuracy of det J at the point,
     * exact in 2D). For points at the centres of a cell's sub-cells (the
     * point generator's) these are the sub-cells themselves: the domains
     * tile the material exactly, also on a distorted mesh, where
     * parallelograms from the Jacobian at the point would overlap and
     * leave gaps by a fixed fraction of a cell at every refinement.
     * With 'CPDI domain size' s != 1 (@p size) the square's edges are s
     * times as long: the domains overlap (s > 1) or leave gaps (s < 1).
     */
    static Offsets
    initial_domain(const std::array<Point<dim>, n_corners> &vertices,
                   const Point<dim>                        &xi,
                   const double                             volume,
                   const double                             size = 1);

    /// 'CPDI domain size': the initial domains' edges over those of the
    /// domains that tile the material.
    double
    initial_domain_size() const
    {
      return domain_size;
    }

    /// The signs s_c of corner @p c (bit d of c is the sign of s_d).
    static Tensor<1, dim>
    corner_signs(const unsigned int c)
    {
      Tensor<1, dim> s;
      for (unsigned int d = 0; d < dim; ++d)
        s[d] = ((c >> d) & 1) ? 1. : -1.;
      return s;
    }

    /// Offsets of the parallelepiped x_p + R s.
    static Offsets
    parallelepiped(const Tensor<2, dim> &R)
    {
      Offsets D;
      for (unsigned int c = 0; c < n_corners; ++c)
        D[c] = R * corner_signs(c);
      return D;
    }

    /**
     * The affine part R of a domain, the least-squares fit of
     * D_c = R s_c: R = 2^-dim sum_c D_c (x) s_c; the domain itself if it
     * is a parallelepiped.
     */
    static Tensor<2, dim>
    affine_part(const Offsets &D)
    {
      Tensor<2, dim> R;
      for (unsigned int c = 0; c < n_corners; ++c)
        R += outer_product(D[c], corner_signs(c));
      return R / n_corners;
    }

    /// Whether the domain @p D is the parallelepiped of its affine part
    /// @p R (to round-off).
    static bool
    is_parallelepiped(const Offsets &D, const Tensor<2, dim> &R)
    {
      const double tolerance = 1e-24 * R.norm_square();
      for (unsigned int c = 0; c < n_corners; ++c)
        if ((D[c] - R * corner_signs(c)).norm_square() > tolerance)
          return false;
      return true;
    }

    /**
     * alpha_c and beta_c (see the class documentation) of the domain with
     * corners @p corners (deal.II's vertex order), by 2^dim-point Gauss
     * quadrature on the domain (exact for a multilinear domain in 2D).
     * Returns false if the domain is inverted at a quadrature point.
     */
    static bool
    corner_weights(const std::array<Point<dim>, n_corners> &corners,
                   std::array<double, n_corners>           &alpha,
                   std::array<Tensor<1, dim>, n_corners>   &beta);

    /**
     * The domain @p D after a deformation step by the velocity gradient
     * times dt, @p dt_grad_v: (I + dt grad v) D_c, or, if that stretches it
     * more than the 'CPDI stretch limit' times the stretch of its cell's
     * own shape (the stretch: the longest half edge of the affine part
     * over the half side of the square or cube of the same volume;
     * @p cell_stretch2 the square of the cell's, cell_stretch2()), that
     * square (cube) turned by the domain's rotation (the orthogonal factor
     * of the polar decomposition of its affine part).
     *
     * Why: in granular flow the deformation gradient of a point grows
     * without bound (shear strains of hundreds), and the domain x_p + F D0
     * becomes a needle many cells long, whose corners then sit in cells
     * that have nothing to do with the point. Measured: without the limit
     * the column collapse at a = 2 created energy (doc/convergence.md).
     * The weights need a domain of the point's volume around it, not its
     * full history, so the shape is reset, as CPDI codes do for large
     * deformation. Relative to the cell: a point in a cell four times as
     * wide as high starts with a domain of that shape (stretch 2 in 2D),
     * which the bare limit reset to a square at its first step, so that a
     * layer at rest on such cells did not stay at rest (a saturated one's
     * pore pressure 31 % off).
     */
    Offsets
    deformed_domain(const Offsets        &D,
                    const Tensor<2, dim> &dt_grad_v,
                    const double          cell_stretch2) const;

    /**
     * The square of the stretch of the domain a cell with vertices
     * @p vertices gives its points (the Jacobian of its map at its
     * centre): the longest edge of the cell's affine part over the side
     * of the square (cube) of its volume. 1 for a square or a cube, and
     * for any cell within 1e-10 of 1.
     */
    static double
    cell_stretch2(const std::array<Point<dim>, n_corners> &vertices);

    /**
     * corner_weights() of the parallelepiped x_p + R s in closed form:
     * alpha_c = 2^-dim, beta_c = R^{-T} s_c / 2^dim. The common case: a
     * domain is a parallelepiped on a mesh of parallelograms.
     */
    static void
    parallelepiped_weights(const Tensor<2, dim>                  &R,
                           std::array<double, n_corners>         &alpha,
                           std::array<Tensor<1, dim>, n_corners> &beta)
    {
      const Tensor<2, dim> inverse_transpose = transpose(invert(R));
      for (unsigned int c = 0; c < n_corners; ++c)
        {
          alpha[c] = 1. / n_corners;
          beta[c]  = (inverse_transpose * corner_signs(c)) / n_corners;
        }
    }

    /// Read the corner offsets from a point's slots @p data.
    static Offsets
    read(const double *data)
    {
      Offsets D;
      for (unsigned int c = 0; c < n_corners; ++c)
        for (unsigned int d = 0; d < dim; ++d)
          D[c][d] = data[c * dim + d];
      return D;
    }

    static void
    write(const Offsets &D, double *data)
    {
      for (unsigned int c = 0; c < n_corners; ++c)
        for (unsigned int d = 0; d < dim; ++d)
          data[c * dim + d] = D[c][d];
    }

  private:
    double          stretch_limit  = 2;
    double          domain_size    = 1;
  };
} // namespace MPM

#endif

#include <mpm/grid/inverse_mapping.h>
#include <mpm/transfer/point_domains.h>

#include <cmath>

namespace MPM
{
  template <int dim>
  void
  PointDomains<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Transfer");
    {
      prm.declare_entry(
        "CPDI stretch limit",
        "2",
        Patterns::Double(1),
        "'cpdi' only: when a point's domain has a half edge longer than "
        "this many times the half side of the square (cube) of the same "
        "volume, times the same ratio of its cell (1 for a square cell), "
        "it is reset to that square, turned by the domain's rotation. "
        "Large flows stretch domains into needles many cells long "
        "otherwise.");
      prm.declare_entry(
        "CPDI domain size",
        "1",
        Patterns::Double(0.01, 2),
        "'cpdi' only: the edges of each point's initial domain over those "
        "of the domains that tile the material (the point's sub-cell, of "
        "the point's volume). 1 is CPDI; above 1 the domains overlap and "
        "average the mesh functions over more than the point's own "
        "volume, below 1 they leave gaps. A diagnostic: it separates the "
        "width over which the weights are smoothed from the number of "
        "points per cell (doc/column_collapse.md, the bullet on the "
        "points per cell).");
    }
    prm.leave_subsection();
  }


  template <int dim>
  void
  PointDomains<dim>::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Transfer");
    stretch_limit = prm.get_double("CPDI stretch limit");
    domain_size   = prm.get_double("CPDI domain size");
    prm.leave_subsection();
  }


  template <int dim>
  std::vector<std::string>
  PointDomains<dim>::point_property_names() const
  {
    std::vector<std::string> names;
    for (unsigned int c = 0; c < n_corners; ++c)
      for (unsigned int d = 0; d < dim; ++d)
        names.push_back("domain_corner" + std::to_string(c) + "_" + "xyz"[d]);
    names.emplace_back("domain_scale");
    return names;
  }


  template <int dim>
  typename PointDomains<dim>::Offsets
  PointDomains<dim>::initial_domain(
    const std::array<Point<dim>, n_corners> &vertices,
    const Point<dim>                        &xi,
    const double                             volume,
    const double                             size)
  {
    // det J at xi, from the map's derivatives.
    Tensor<2, dim> J;
    for (unsigned int i = 0; i < vertices.size(); ++i)
      for (unsigned int e = 0; e < dim; ++e)
        {
          double g = ((i >> e) & 1) ? 1. : -1.;
          for (unsigned int d = 0; d < dim; ++d)
            if (d != e)
              g *= ((i >> d) & 1) ? xi[d] : 1. - xi[d];
          for (unsigned int a = 0; a < dim; ++a)
            J[a][e] += g * (vertices[i][a] - vertices[0][a]);
        }
    const double half =
      0.5 * size * std::pow(volume / determinant(J), 1. / dim);
    const Point<dim> x = map_unit_to_real<dim>(vertices, xi);
    Offsets          D;
    for (unsigned int c = 0; c < n_corners; ++c)
      D[c] = map_unit_to_real<dim>(vertices, xi + half * corner_signs(c)) - x;
    return D;
  }


  namespace
  {
    /// The largest squared length of the columns of @p R (the edges of a
    /// domain's or a cell's affine part).
    template <int dim>
    double
    longest_column2(const Tensor<2, dim> &R)
    {
      double longest2 = 0;
      for (unsigned int b = 0; b < dim; ++b)
        {
          double length2 = 0;
          for (unsigned int a = 0; a < dim; ++a)
            length2 += R[a][b] * R[a][b];
          longest2 = std::max(longest2, length2);
        }
      return longest2;
    }
  } // namespace


  template <int dim>
  double
  PointDomains<dim>::cell_stretch2(
    const std::array<Point<dim>, n_corners> &vertices)
  {
    // J at the centre: each column the mean of the cell's edges along
    // that reference direction.
    Tensor<2, dim> J;
    for (unsigned int i = 0; i < n_corners; ++i)
      for (unsigned int e = 0; e < dim; ++e)
        {
          const double g = (((i >> e) & 1) ? 1. : -1.) / (n_corners / 2);
          for (unsigned int a = 0; a < dim; ++a)
            J[a][e] += g * vertices[i][a];
        }
    const double longest2 = longest_column2(J);
    const double det      = std::abs(determinant(J));
    const double stretch2 = det > 0 ? longest2 / std::pow(det, 2. / dim) : 1.;
    return stretch2 < 1 + 1e-10 ? 1. : stretch2;
  }


  template <int dim>
  typename PointDomains<dim>::Offsets
  PointDomains<dim>::deformed_domain(const Offsets        &D,
                                     const Tensor<2, dim> &dt_grad_v,
                                     const double          cell_stretch2) const
  {
    Offsets deformed;
    for (unsigned int c = 0; c < n_corners; ++c)
      deformed[c] = D[c] + dt_grad_v * D[c];
    const Tensor<2, dim> R   = affine_part(deformed);
    const double         det = determinant(R);
    const double         longest2 = longest_column2(R);
    // longest^2 <= limit^2 side^2 with side^2 = |det|^(2/dim), in 3D
    // compared cubed (longest^6 <= limit^6 det^2): no pow() for the
    // domains within the limit, nearly all of them (pow() was 2 % of a
    // CPDI step). In 2D side^2 is |det| itself.
    const double limit2 = stretch_limit * stretch_limit * cell_stretch2;
    const bool   within =
      dim == 2 ? longest2 <= limit2 * std::abs(det) :
                 longest2 * longest2 * longest2 <=
                   limit2 * limit2 * limit2 * (det * det);
    if (!(det > 0) || within)
      return deformed;
    const double side2 = std::pow(std::abs(det), 2. / dim);
    // The rotation of the polar decomposition (det R > 0 here).
    const Tensor<2, dim> Q = project_onto_orthogonal_tensors(R);
    return parallelepiped(std::sqrt(side2) * Q);
  }


  template <int dim>
  bool
  PointDomains<dim>::corner_weights(
    const std::array<Point<dim>, n_corners> &corners,
    std::array<double, n_corners>           &alpha,
    std::array<Tensor<1, dim>, n_corners>   &beta)
  {
    if constexpr (dim == 2)
      {
        // Closed form for a quadrilateral: with x(xi, eta) = x0 + b xi +
        // c eta + d xi eta, det J = a0 + a1 xi + a2 eta is linear, so
        // int M_c det J and the area are exact polynomials; and
        // int grad M_c = (boundary integral of M_c n) = half the outward
        // normals of the two edges at c: with the corners in
        // counter-clockwise order (0, 1, 3, 2), n and p the next and the
        // previous corner of c, beta_c V = (y_n - y_p, x_p - x_n) / 2.
        const Tensor<1, 2> b = corners[1] - corners[0];
        const Tensor<1, 2> c = corners[2] - corners[0];
        const Tensor<1, 2> d = corners[3] - corners[1] - c;
        const auto cross = [](const Tensor<1, 2> &u, const Tensor<1, 2> &v) {
          return u[0] * v[1] - u[1] * v[0];
        };
        const double a0 = cross(b, c), a1 = cross(b, d), a2 = cross(d, c);
        if (!(a0 > 0 && a0 + a1 > 0 && a0 + a2 > 0 && a0 + a1 + a2 > 0))
          return false;
        const double volume = a0 + 0.5 * (a1 + a2);
        // Counter-clockwise neighbours in deal.II's numbering.
        constexpr unsigned int next[4]     = {1, 3, 0, 2};
        constexpr unsigned int previous[4] = {2, 0, 3, 1};
        for (unsigned int k = 0; k < 4; ++k)
          {
            const double int_xi  = (k & 1) ? 1. / 6. : 1. / 12.;
            const double int_eta = (k & 2) ? 1. / 6. : 1. / 12.;
            alpha[k] = (0.25 * a0 + a1 * int_xi + a2 * int_eta) / volume;
            const Point<2> &xn = corners[next[k]], &xp = corners[previous[k]];
            beta[k][0]         = 0.5 * (xn[1] - xp[1]) / volume;
            beta[k][1]         = 0.5 * (xp[0] - xn[0]) / volume;
          }
        return true;
      }
    else
      {
        // 2 x 2 x 2-point Gauss quadrature on the hexahedral domain, exact
        // for a trilinear domain: det J is of degree 2 in each coordinate,
        // M_c det J and cof(J) grad M_c of degree 3. det J J^-T is the
        // cofactor matrix, whose columns are cross products of the
        // Jacobian's: no division per quadrature point. The shape
        // functions M_c and their reference gradients at the quadrature
        // points are the same for every domain: tabulated once.
        struct Table
        {
          double         M[8][8];
          Tensor<1, 3>   dM[8][8];
        };
        static const Table table = [] {
          Table        t;
          const double gauss[2] = {0.5 - 0.5 / std::sqrt(3.),
                                   0.5 + 0.5 / std::sqrt(3.)};
          for (unsigned int q = 0; q < 8; ++q)
            {
              Point<3> xi;
              for (unsigned int d = 0; d < 3; ++d)
                xi[d] = gauss[(q >> d) & 1];
              for (unsigned int c = 0; c < 8; ++c)
                {
                  t.M[q][c] = 1;
                  for (unsigned int d = 0; d < 3; ++d)
                    t.M[q][c] *= ((c >> d) & 1) ? xi[d] : 1. - xi[d];
                  for (unsigned int e = 0; e < 3; ++e)
                    {
                      double g = ((c >> e) & 1) ? 1. : -1.;
                      for (unsigned int d = 0; d < 3; ++d)
                        if (d != e)
                          g *= ((c >> d) & 1) ? xi[d] : 1. - xi[d];
                      t.dM[q][c][e] = g;
                    }
                }
            }
          return t;
        }();
        std::array<Tensor<1, 3>, 8> offset;
        for (unsigned int c = 1; c < 8; ++c)
          offset[c] = corners[c] - corners[0];
        alpha.fill(0.);
        beta.fill(Tensor<1, dim>());
        double volume = 0;
        for (unsigned int q = 0; q < 8; ++q)
          {
            // The Jacobian's columns j_e = sum_c (x_c - x_0) dM_c / dxi_e
            // (quadrature weight 1/8, dropped: it cancels in the ratios).
            Tensor<1, 3> j[3];
            for (unsigned int c = 1; c < 8; ++c)
              for (unsigned int e = 0; e < 3; ++e)
                j[e] += table.dM[q][c][e] * offset[c];
            const Tensor<1, 3> k0  = cross_product_3d(j[1], j[2]);
            const Tensor<1, 3> k1  = cross_product_3d(j[2], j[0]);
            const Tensor<1, 3> k2  = cross_product_3d(j[0], j[1]);
            const double       det = j[0] * k0;
            if (!(det > 0))
              return false;
            volume += det;
            for (unsigned int c = 0; c < 8; ++c)
              {
                alpha[c] += table.M[q][c] * det;
                beta[c] += table.dM[q][c][0] * k0 + table.dM[q][c][1] * k1 +
                           table.dM[q][c][2] * k2;
              }
          }
        for (unsigned int c = 0; c < n_corners; ++c)
          {
            alpha[c] /= volume;
            beta[c] /= volume;
          }
        return true;
      }
  }


  template class PointDomains<2>;
  template class PointDomains<3>;
} // namespace MPM

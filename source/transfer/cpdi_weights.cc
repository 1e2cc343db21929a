// The particle-grid passes with CPDI weights (CpdiWeights, PointDomains):
// every point acts on the nodes through the corners of its domain.

#include <deal.II/base/mpi.h>
#include <deal.II/base/tensor.h>
#include <deal.II/grid/grid_tools.h>

#include <mpm/grid/inverse_mapping.h>
#include <mpm/material_points/property_layout.h>
#include <mpm/transfer/cpdi_weights.h>

#include <limits>
#include <sstream>

namespace MPM
{
  namespace
  {
    /// Whether @p x lies in the bounding box of @p vertices enlarged by
    /// @p margin times its size: the cheap rejection before an inverse
    /// map (most candidate cells of a corner do not contain it, and the
    /// inverse map of a non-affine cell is dearest for points outside).
    template <int dim>
    bool
    in_bounding_box(
      const std::array<Point<dim>, GeometryInfo<dim>::vertices_per_cell>
                       &vertices,
      const Point<dim> &x,
      const double      margin)
    {
      for (unsigned int d = 0; d < dim; ++d)
        {
          double lo = vertices[0][d], hi = lo;
          for (unsigned int v = 1; v < vertices.size(); ++v)
            {
              lo = std::min(lo, vertices[v][d]);
              hi = std::max(hi, vertices[v][d]);
            }
          const double slack = margin * (hi - lo) + 1e-12 * (hi - lo);
          if (x[d] < lo - slack || x[d] > hi + slack)
            return false;
        }
      return true;
    }


    /// Whether the cell with @p vertices (and, in 2D, @p map) contains
    /// @p x, and its reference coordinates @p xi there.
    template <int dim>
    bool
    cell_contains(
      const std::array<Point<dim>, GeometryInfo<dim>::vertices_per_cell>
                            &vertices,
      const BilinearCellMap *map,
      const Point<dim>      &x,
      Point<dim>            &xi)
    {
      if constexpr (dim == 2)
        {
          // The bilinear cell is the convex quadrilateral of its straight
          // edges: outside one edge's line (by more than round-off) is
          // outside the cell, four cross products instead of the inverse
          // map, which is dearest for the points outside a non-affine cell.
          const Point<2> *v[4] = {&vertices[0],
                                  &vertices[1],
                                  &vertices[3],
                                  &vertices[2]};
          const Tensor<1, 2> d1 = *v[2] - *v[0], d2 = *v[3] - *v[1];
          const double orientation = d1[0] * d2[1] - d1[1] * d2[0] > 0 ? 1. : -1.;
          for (unsigned int e = 0; e < 4; ++e)
            {
              const Tensor<1, 2> edge = *v[(e + 1) % 4] - *v[e];
              const double side = orientation * (edge[0] * (x[1] - (*v[e])[1]) -
                                                 edge[1] * (x[0] - (*v[e])[0]));
              if (side < -1e-10 * edge.norm_square())
                return false;
            }
          return map->contains(x, xi);
        }
      else
        {
          (void)map;
          if (!in_bounding_box<dim>(vertices, x, 0.))
            return false;
          const auto result = inverse_map_newton<dim>(vertices, x);
          if (!result.success || !inside_unit_cell(result.xi))
            return false;
          xi = result.xi;
          return true;
        }
    }


    /// The dim x dim part of a point's stress.
    template <int dim>
    Tensor<2, dim>
    in_plane_stress(const double *props)
    {
      const SymmetricTensor<2, 3> stress =
        read_symmetric_tensor(&props[PropertyLayout<dim>::stress]);
      Tensor<2, dim> sigma;
      for (unsigned int a = 0; a < dim; ++a)
        for (unsigned int b = 0; b < dim; ++b)
          sigma[a][b] = stress[a][b];
      return sigma;
    }


    /// A corner's force before its shape function values: -V sigma beta_c
    /// + alpha_c m g (f_i = N_i(x_c) times this).
    template <int dim>
    Tensor<1, dim>
    corner_force(const double         *props,
                 const double          alpha,
                 const Tensor<1, dim> &beta,
                 const Tensor<1, dim> &g)
    {
      using Layout = PropertyLayout<dim>;
      return -props[Layout::volume] * (in_plane_stress<dim>(props) * beta) +
             (alpha * props[Layout::mass]) * g;
    }
  } // namespace


  template <int dim>
  CpdiWeights<dim>::CpdiWeights(const TransferContext<dim> &context,
                                ParameterHandler           &prm)
    : ParticleGridWeights<dim>(context)
  {
    point_domains.parse_parameters(prm);
  }


  template <int dim>
  void
  CpdiWeights<dim>::setup_partition()
  {
    ParticleGridWeights<dim>::setup_partition();
    // Each cell's patch: itself first, then the non-artificial cells
    // sharing a vertex with it (where the corners may lie).
    const auto &triangulation = this->context.grid.triangulation;
    const auto  sets = GridTools::vertex_to_cell_map(triangulation);
    cell_patches.assign(triangulation.n_active_cells(), {});
    corner_slot_of_cell.assign(triangulation.n_active_cells(),
                               numbers::invalid_unsigned_int);
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          auto &patch = cell_patches[cell->active_cell_index()];
          patch.push_back(cell);
          for (const unsigned int v : cell->vertex_indices())
            for (const auto &neighbour : sets[cell->vertex_index(v)])
              if (!neighbour->is_artificial() &&
                  std::find(patch.begin(), patch.end(), neighbour) ==
                    patch.end())
                patch.push_back(neighbour);
        }
  }


  template <int dim>
  double
  CpdiWeights<dim>::prepare()
  {
    auto       &particle_handler = this->context.particle_handler;
    const auto &grid             = this->context.grid;
    const unsigned int step      = this->context.step;
    const unsigned int domain_slot = this->own_slot;
    auto       &point_properties = this->points;
    auto       &shape_functions  = this->shape_functions;
    TimerOutput::Scope     t(this->context.timer, "shape functions");
    constexpr unsigned int n_corners = PointDomains<dim>::n_corners;
    using CellIterator = typename Triangulation<dim>::active_cell_iterator;
    using Layout       = PropertyLayout<dim>;
    const unsigned int n_points =
      particle_handler.n_locally_owned_particles();
    point_properties.resize(n_points);
    point_cell_map.resize(n_points);

    // This step's corners, in the order of the points (reused storage).
    auto &corners = located_corners;
    corners.clear();

    unsigned int p = 0;
    point_cell_begin.clear();
    for (auto it = particle_handler.begin(); it != particle_handler.end();)
      {
        point_cell_begin.push_back(p);
        const CellIterator cell   = it->get_surrounding_cell();
        const auto         points = particle_handler.particles_in_cell(cell);
        const auto        &patch  = cell_patches[cell->active_cell_index()];
        // The patch's geometry, looked up once for the cell's points, and
        // where each corner was found for the previous point (the points
        // of a cell are alike: tried first).
        std::array<const std::array<Point<dim>, n_corners> *, 64> vertices_of;
        std::array<const BilinearCellMap *, 64>                   map_of;
        AssertThrow(patch.size() <= 64, ExcInternalError());
        for (unsigned int i = 0; i < patch.size(); ++i)
          {
            vertices_of[i] = &grid.cell_vertices(patch[i]);
            map_of[i] = dim == 2 ? &grid.bilinear_map(patch[i]) : nullptr;
          }
        std::array<unsigned int, n_corners> last_found;
        last_found.fill(0);
        for (auto point = points.begin(); point != points.end(); ++point, ++p)
          {
            double *props       = point->get_properties().data();
            point_properties[p] = props;
            point_cell_map[p] =
              dim == 2 ? &grid.bilinear_map(cell) : nullptr;
            // A point without a domain yet (new, or read from a file) gets
            // the one of PointDomains::initial_domain().
            auto D = PointDomains<dim>::read(props + domain_slot);
            if (D[0].norm_square() == 0)
              {
                D = PointDomains<dim>::initial_domain(
                  grid.cell_vertices(cell),
                  point->get_reference_location(),
                  props[Layout::volume]);
                PointDomains<dim>::write(D, props + domain_slot);
                props[domain_slot + PointDomains<dim>::scale_slot] = 1;
              }
            const Point<dim> x_p = point->get_location();
            std::array<Point<dim>, n_corners>   x;
            std::array<CellIterator, n_corners> corner_cell;
            std::array<Point<dim>, n_corners>   xi;
            // Whether the corners are still x_p + s D_c (none moved onto a
            // cell).
            bool parallelepiped = true;
            // Whether @p y lies within 2 % of the reference cell of
            // @p candidate; if so @p y is moved onto the cell (its
            // reference coordinates clamped to [0, 1]) and @p eta are they,
            // with corner_cell set.
            const auto nearly_contains = [&](const CellIterator &candidate,
                                             Point<dim>         &y,
                                             Point<dim>         &eta) {
              const auto &vertices = grid.cell_vertices(candidate);
              if (!in_bounding_box<dim>(vertices, y, 0.05))
                return false;
              InverseMappingResult<dim> result;
              if constexpr (dim == 2)
                result = grid.bilinear_map(candidate).inverse(y);
              else
                result = inverse_map_newton<dim>(vertices, y);
              if (!result.success || !inside_unit_cell(result.xi, 0.02))
                return false;
              for (unsigned int d = 0; d < dim; ++d)
                eta[d] = std::min(1., std::max(0., result.xi[d]));
              y                  = map_unit_to_real<dim>(vertices, eta);
              parallelepiped = false;
              return true;
            };
            // Whether every corner of the domain scaled by s about x_p
            // lies in the patch (and where).
            const auto locate_corners = [&](const double s) {
              parallelepiped = true;
              for (unsigned int c = 0; c < n_corners; ++c)
                {
                  x[c] =
                    x_p + s * D[c];
                  bool found = false;
                  for (unsigned int j = 0; j <= patch.size(); ++j)
                    {
                      // The previous point's cell of this corner first.
                      const unsigned int i =
                        j == 0 ? last_found[c] :
                                 (j - 1 == last_found[c] ? 0 : j - 1);
                      if (j > 0 && j - 1 == 0 && last_found[c] == 0)
                        continue;
                      if (cell_contains<dim>(*vertices_of[i],
                                             map_of[i],
                                             x[c],
                                             xi[c]))
                        {
                          corner_cell[c] = patch[i];
                          last_found[c]  = i;
                          found          = true;
                          break;
                        }
                    }
                  // Just outside every cell of the patch (a domain built
                  // from the Jacobian at the point pokes out of a
                  // distorted boundary cell by O(distortion * size^2)):
                  // moved onto the nearest cell's boundary.
                  for (unsigned int i = 0; !found && i < patch.size(); ++i)
                    if (nearly_contains(patch[i], x[c], xi[c]))
                      {
                        corner_cell[c] = patch[i];
                        found          = true;
                      }
                  if (!found)
                    return false;
                }
              return true;
            };
            // The scale s of the domain about the point: 1 unless a corner
            // left the patch (beyond the mesh or a wall, or past the
            // neighbours). Then the whole domain is shrunk about the point,
            // so that it stays centred on it: a point next to a wall moves
            // with the wall's nodes, as with linear weights, instead of
            // being pulled through it by its far corners. The scale is kept
            // from step to step (the last slot) and tried to be doubled
            // every 8th step, so a point resting against a wall pays for
            // one try most steps, not a bisection.
            double &scale = props[domain_slot + PointDomains<dim>::scale_slot];
            const double grown =
              step % 8 == 0 ? std::min(1., 2 * scale) : scale;
            if (locate_corners(grown))
              scale = grown;
            else if (!(scale < grown && locate_corners(scale)))
              {
                double inside = 0, outside = std::min(scale, grown);
                for (unsigned int i = 0; i < 10; ++i)
                  {
                    const double s = 0.5 * (inside + outside);
                    (locate_corners(s) ? inside : outside) = s;
                  }
                scale = inside;
                if (inside == 0 || !locate_corners(inside))
                  {
                    // The point sits on the patch's edge: a domain a
                    // millionth of its size in its own cell, its corners'
                    // reference coordinates extrapolated if they are just
                    // outside (the limit is the linear weights).
                    scale          = 1e-6;
                    parallelepiped = true;
                    for (unsigned int c = 0; c < n_corners; ++c)
                      {
                        x[c] = x_p + scale * D[c];
                        corner_cell[c] = cell;
                        if constexpr (dim == 2)
                          xi[c] = grid.bilinear_map(cell).inverse(x[c]).xi;
                        else
                          xi[c] = inverse_map_newton<dim>(
                                    grid.cell_vertices(cell), x[c])
                                    .xi;
                      }
                  }
              }
            std::array<double, n_corners>         alpha;
            std::array<Tensor<1, dim>, n_corners> beta;
            const Tensor<2, dim> R = PointDomains<dim>::affine_part(D);
            if (parallelepiped && PointDomains<dim>::is_parallelepiped(D, R))
              PointDomains<dim>::parallelepiped_weights(scale * R,
                                                        alpha,
                                                        beta);
            else if (!PointDomains<dim>::corner_weights(x, alpha, beta))
              {
                std::ostringstream s;
                s << "The CPDI domain of material point " << point->get_id()
                  << " at (" << x_p << ") is inverted (domain vectors "
                  << R << " as a parallelogram): the material it represents has turned inside "
                  << "out; reduce the time step.";
                throw std::runtime_error(s.str());
              }
            // The affine centre (see corner_offset).
            Tensor<1, dim> shift;
            for (unsigned int c = 0; c < n_corners; ++c)
              shift += alpha[c] * (x[c] - x_p);
            for (unsigned int c = 0; c < n_corners; ++c)
              corners.push_back({corner_cell[c],
                                 p,
                                 xi[c],
                                 alpha[c],
                                 beta[c],
                                 (x[c] - x_p) - shift});
          }
        it = points.end();
      }
    point_cell_begin.push_back(p);

    // Group the corners by cell (a counting sort in the order in which the
    // cells were first touched), so that each pass adds to a cell's nodes
    // once for all corners in it.
    // slot_of_cell (as long as the mesh, set up with the nodal fields) is
    // reset below for the touched cells only: no per-step cost in the size
    // of the mesh.
    auto &slot_of_cell = corner_slot_of_cell;
    std::vector<CellIterator> touched;
    std::vector<unsigned int> count;
    for (const auto &corner : corners)
      {
        unsigned int &slot = slot_of_cell[corner.cell->active_cell_index()];
        if (slot == numbers::invalid_unsigned_int)
          {
            slot = touched.size();
            touched.push_back(corner.cell);
            count.push_back(0);
          }
        ++count[slot];
      }
    std::vector<unsigned int> next(touched.size() + 1, 0);
    for (unsigned int s = 0; s < touched.size(); ++s)
      next[s + 1] = next[s] + count[s];
    shape_functions.resize(corners.size());
    corner_point.resize(corners.size());
    corner_alpha.resize(corners.size());
    corner_beta.resize(corners.size());
    const bool affine = this->affine();
    if (affine)
      corner_offset.resize(corners.size());
    for (const auto &corner : corners)
      {
        const unsigned int k =
          next[slot_of_cell[corner.cell->active_cell_index()]]++;
        if constexpr (dim == 2)
          this->shape_functions[k].reinit(grid.bilinear_map(corner.cell),
                                          corner.xi);
        else
          this->shape_functions[k].reinit(grid.cell_vertices(corner.cell),
                                    corner.xi);
        corner_point[k] = corner.point;
        corner_alpha[k] = corner.alpha;
        corner_beta[k]  = corner.beta;
        if (affine)
          corner_offset[k] = corner.offset;
      }
    for (const CellIterator &cell : touched)
      slot_of_cell[cell->active_cell_index()] = numbers::invalid_unsigned_int;

    this->clear_active_cells();
    for (unsigned int s = 0; s < touched.size(); ++s)
      this->add_active_cell(touched[s], count[s]);
    return this->finish_active_cells();
  }


  template <int dim>
  void
  CpdiWeights<dim>::map_mass_and_momentum(const bool with_forces)
  {
    TimerOutput::Scope     t(this->context.timer, "particle to grid");
    using Layout                      = PropertyLayout<dim>;
    const Tensor<1, dim>   g          = this->context.time_stepping.gravity;
    const bool affine = this->affine();
    unsigned int           k          = 0;
    if (affine)
      {
        // APIC: each point's affine matrix at its weights of this step,
        // which needs its second moment D_p summed over its corners first
        // (Apic::affine_matrix()).
        const unsigned int n_points = this->points.size();
        second_moments(point_sum_D);
        point_affine.resize(n_points);
        for (unsigned int p = 0; p < n_points; ++p)
          point_affine[p] = this->context.transfer.apic()->affine_matrix(
            this->points[p] + this->transfer_slot, point_sum_D[p]);
      }
    for (const auto &cell : this->active_cells)
      {
        VertexValues mass, momentum, forces;
        for (unsigned int q = 0; q < cell.n_points; ++q, ++k)
          {
            const double *props = this->points[corner_point[k]];
            const double  m     = corner_alpha[k] * props[Layout::mass];
            const auto    v     = read_vector<dim>(&props[Layout::velocity]);
            const auto   &N     = this->shape_functions[k].value;
            if (affine)
              {
                // Each node receives the point's affine field there,
                // v_p + C_p (x_i - xbar_p).
                const auto dx = corner_node_offsets(cell, k);
                this->add_mass_and_momentum(N,
                                      m,
                                      v,
                                      &point_affine[corner_point[k]],
                                      &dx,
                                      mass,
                                      momentum);
              }
            else
              this->add_mass_and_momentum(
                N, m, v, nullptr, nullptr, mass, momentum);
            if (with_forces)
              {
                // f_i = -V sigma grad w_i + w_i m g, corner by corner.
                const Tensor<1, dim> f =
                  corner_force<dim>(props, corner_alpha[k], corner_beta[k], g);
                for (unsigned int i = 0; i < n_vertices; ++i)
                  forces[i] += N[i] * f;
              }
          }
        this->add_to_nodes(cell, mass, this->context.nodal.mass);
        this->add_to_nodes(cell, momentum, this->context.nodal.momentum);
        if (with_forces)
          this->add_to_nodes(cell, forces, this->context.nodal.force);
      }
    this->add_contributions_of_all_ranks(this->context.nodal.mass);
    this->add_contributions_of_all_ranks(this->context.nodal.momentum);
    if (with_forces)
      this->add_contributions_of_all_ranks(this->context.nodal.force);
  }


  template <int dim>
  void
  CpdiWeights<dim>::map_forces()
  {
    TimerOutput::Scope     t(this->context.timer, "particle to grid");
    const Tensor<1, dim>   g          = this->context.time_stepping.gravity;
    unsigned int           k          = 0;
    for (const auto &cell : this->active_cells)
      {
        VertexValues forces;
        for (unsigned int q = 0; q < cell.n_points; ++q, ++k)
          {
            const Tensor<1, dim> f =
              corner_force<dim>(this->points[corner_point[k]],
                                corner_alpha[k],
                                corner_beta[k],
                                g);
            const auto &N = this->shape_functions[k].value;
            for (unsigned int i = 0; i < n_vertices; ++i)
              forces[i] += N[i] * f;
          }
        this->add_to_nodes(cell, forces, this->context.nodal.force);
      }
    this->add_contributions_of_all_ranks(this->context.nodal.force);
  }


  template <int dim>
  double
  CpdiWeights<dim>::update_points_from_grid(const bool remap_momentum)
  {
    auto &particle_handler = this->context.particle_handler;
    auto &updater          = this->context.point_update;
    TimerOutput::Scope     t(this->context.timer, "grid to particle");
    using Layout                      = PropertyLayout<dim>;
    const unsigned int     n_points   = this->points.size();
    // 1. Each point's interpolated acceleration and velocity, summed over
    //    its corners.
    point_sum_a.assign(n_points, Tensor<1, dim>());
    point_sum_b.assign(n_points, Tensor<1, dim>());
    // APIC: B_p, D_p and the velocity gradient of the end-of-step grid
    // velocity, for C_p = B_p D_p^{-1} (Apic::fit_affine()).
    const bool affine = this->affine();
    if (affine)
      {
        point_sum_B.assign(n_points, Tensor<2, dim>());
        point_sum_D.assign(n_points, Tensor<2, dim>());
        point_sum_gradient.assign(n_points, Tensor<2, dim>());
        point_node_scale.assign(n_points, 0.);
      }
    unsigned int k = 0;
    for (const auto &cell : this->active_cells)
      {
        const VertexValues a_node =
          this->read_nodes(cell, this->context.nodal.acceleration);
        const VertexValues v_node =
          this->read_nodes(cell, this->context.nodal.velocity_new);
        for (unsigned int q = 0; q < cell.n_points; ++q, ++k)
          {
            const auto    &N = this->shape_functions[k].value;
            Tensor<1, dim> a, v;
            for (unsigned int i = 0; i < n_vertices; ++i)
              {
                a += N[i] * a_node[i];
                v += N[i] * v_node[i];
              }
            const unsigned int p = corner_point[k];
            point_sum_a[p] += corner_alpha[k] * a;
            point_sum_b[p] += corner_alpha[k] * v;
            if (affine)
              {
                const auto   dx    = corner_node_offsets(cell, k);
                const double alpha = corner_alpha[k];
                for (unsigned int i = 0; i < n_vertices; ++i)
                  {
                    const Tensor<1, dim> w_dx = (alpha * N[i]) * dx[i];
                    point_sum_B[p] += outer_product(v_node[i], w_dx);
                    point_sum_D[p] += outer_product(w_dx, dx[i]);
                    point_node_scale[p] =
                      std::max(point_node_scale[p], dx[i].norm_square());
                  }
                point_sum_gradient[p] += outer_product(v, corner_beta[k]);
              }
          }
      }
    // 2. The points, in the order of this->points.
    double       v_max2 = 0;
    unsigned int p      = 0;
    for (auto point = particle_handler.begin(); point != particle_handler.end();
         ++point, ++p)
      {
        updater.advance(point,
                      this->points[p],
                      point_sum_a[p],
                      point_sum_b[p],
                      point_cell_map[p],
                      v_max2);
        if (affine)
          point_affine[p] =
            Apic<dim>::fit_affine(point_sum_B[p],
                                              point_sum_D[p],
                                              point_sum_gradient[p],
                                              point_node_scale[p],
                                              this->points[p] +
                                                this->transfer_slot);
      }
    // 3. MUSL: the points' new momentum back to the nodes.
    if (remap_momentum)
      {
        this->zero_touched_entries(this->context.nodal.momentum);
        k = 0;
        for (const auto &cell : this->active_cells)
          {
            VertexValues remapped;
            for (unsigned int q = 0; q < cell.n_points; ++q, ++k)
              {
                const double *props = this->points[corner_point[k]];
                const double  m = corner_alpha[k] * props[Layout::mass];
                const Tensor<1, dim> v =
                  read_vector<dim>(&props[Layout::velocity]);
                const auto &N = this->shape_functions[k].value;
                if (affine)
                  {
                    // APIC's particle-to-grid with the new C_p.
                    const auto            dx = corner_node_offsets(cell, k);
                    const Tensor<2, dim> &C  = point_affine[corner_point[k]];
                    for (unsigned int i = 0; i < n_vertices; ++i)
                      remapped[i] += (N[i] * m) * (v + C * dx[i]);
                  }
                else
                  for (unsigned int i = 0; i < n_vertices; ++i)
                    remapped[i] += (N[i] * m) * v;
              }
            this->add_to_nodes(cell, remapped, this->context.nodal.momentum);
          }
        this->add_contributions_of_all_ranks(this->context.nodal.momentum);
      }
    return v_max2;
  }


  template <int dim>
  void
  CpdiWeights<dim>::update_stress(const NodalVector &velocity,
                                  const bool /*set_affine: C_p is fitted in
                                               update_points_from_grid()*/)
  {
    TimerOutput::Scope     t(this->context.timer, "stress update");
    const unsigned int     n_points   = this->points.size();
    // grad v_p = sum_i v_i (x) grad w_i = sum_c v(x_c) (x) beta_c.
    point_sum_gradient.assign(n_points, Tensor<2, dim>());
    unsigned int k = 0;
    for (const auto &cell : this->active_cells)
      {
        const VertexValues v_node = this->read_nodes(cell, velocity);
        for (unsigned int q = 0; q < cell.n_points; ++q, ++k)
          {
            const auto    &N = this->shape_functions[k].value;
            Tensor<1, dim> v;
            for (unsigned int i = 0; i < n_vertices; ++i)
              v += N[i] * v_node[i];
            point_sum_gradient[corner_point[k]] +=
              outer_product(v, corner_beta[k]);
          }
      }
    const auto  &updater = this->context.point_update;
    const double dt      = this->context.time_step;
    if (updater.averages_volumetric_strain())
      for (unsigned int g = 0; g + 1 < point_cell_begin.size(); ++g)
        PointUpdate<dim>::average_volumetric_part(
          this->points.data() + point_cell_begin[g],
          point_sum_gradient.data() + point_cell_begin[g],
          point_cell_begin[g + 1] - point_cell_begin[g]);
    for (unsigned int p = 0; p < n_points; ++p)
      {
        double              *props  = this->points[p];
        const Tensor<2, dim> grad_v = point_sum_gradient[p];
        updater.update_stress(props, grad_v);
        // The domain deforms with the point: D_c <- (I + dt grad v) D_c.
        const auto D = PointDomains<dim>::read(props + this->own_slot);
        PointDomains<dim>::write(point_domains.deformed_domain(D, dt * grad_v),
                                 props + this->own_slot);
      }
  }


  template <int dim>
  void
  CpdiWeights<dim>::round_trip(const NodalVector &round_trip_velocity,
                               NodalVector       &round_trip_momentum)
  {
    using Layout                      = PropertyLayout<dim>;
    // S+: each point's velocity, summed over its corners.
    point_sum_b.assign(this->points.size(), Tensor<1, dim>());
    unsigned int k = 0;
    for (const auto &cell : this->active_cells)
      {
        const VertexValues u_node =
          this->read_nodes(cell, round_trip_velocity);
        for (unsigned int q = 0; q < cell.n_points; ++q, ++k)
          {
            const auto    &N = this->shape_functions[k].value;
            Tensor<1, dim> v;
            for (unsigned int i = 0; i < n_vertices; ++i)
              v += N[i] * u_node[i];
            point_sum_b[corner_point[k]] += corner_alpha[k] * v;
          }
      }
    // S: the points' momentum back to the nodes with the same weights.
    this->zero_touched_entries(round_trip_momentum);
    k = 0;
    for (const auto &cell : this->active_cells)
      {
        VertexValues sums;
        for (unsigned int q = 0; q < cell.n_points; ++q, ++k)
          {
            const unsigned int   p = corner_point[k];
            const Tensor<1, dim> mv =
              (corner_alpha[k] * this->points[p][Layout::mass]) *
              point_sum_b[p];
            const auto &N = this->shape_functions[k].value;
            for (unsigned int i = 0; i < n_vertices; ++i)
              sums[i] += N[i] * mv;
          }
        this->add_to_nodes(cell, sums, round_trip_momentum);
      }
    this->add_contributions_of_all_ranks(round_trip_momentum);
  }


  template <int dim>
  typename CpdiWeights<dim>::VertexValues
  CpdiWeights<dim>::corner_node_offsets(const ActiveCell  &cell,
                                      const unsigned int k) const
  {
    // x_i - xbar_p = (x_i - x_c) + (x_c - xbar_p).
    auto dx = this->vertex_offsets(cell, this->shape_functions[k]);
    for (auto &d : dx)
      d += corner_offset[k];
    return dx;
  }


  template <int dim>
  void
  CpdiWeights<dim>::second_moments(std::vector<Tensor<2, dim>> &D) const
  {
    // D_p = sum_c alpha_c sum_i N_i(x_c) dx_i dx_i^T about the affine
    // centre.
    D.assign(this->points.size(), Tensor<2, dim>());
    unsigned int k = 0;
    for (const auto &cell : this->active_cells)
      for (unsigned int q = 0; q < cell.n_points; ++q, ++k)
        D[corner_point[k]] +=
          corner_alpha[k] *
          Apic<dim>::second_moment(this->shape_functions[k].value,
                                               corner_node_offsets(cell, k));
  }


  template class CpdiWeights<2>;
  template class CpdiWeights<3>;
} // namespace MPM

MPM_REGISTER_PARTICLE_GRID_WEIGHTS(MPM::CpdiWeights,
                                   "cpdi",
                                   "the mesh functions averaged over each "
                                   "point's deforming parallelogram domain "
                                   "(Sadeghirad et al. 2011).")

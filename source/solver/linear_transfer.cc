// The Simulator's particle-grid passes with the mesh's own linear weights
// (bilinear / trilinear functions at each point): preparing the shape
// functions of the points of each cell, particle-to-grid (mass, momentum
// with APIC's affine part, forces), XPIC's round trip, and grid-to-particle
// (the FLIP/PIC blend, APIC's affine fit, MUSL's remap). Each pass hands
// over to its CPDI counterpart (cpdi_transfer.cc) when the points carry
// domains. The per-point arithmetic of the transfer schemes is in
// VelocityTransfer; the order of the passes in Simulator::do_time_step().

#include <deal.II/base/mpi.h>
#include <deal.II/base/tensor.h>

#include <mpm/material_points/property_layout.h>
#include <mpm/solver/simulator.h>
#include <mpm/transfer/point_domains.h>
#include <mpm/transfer/velocity_transfer.h>

#include <limits>

namespace MPM
{
  template <int dim>
  void
  Simulator<dim>::initialize_affine_matrices()
  {
    // The generator wrote the initial velocity gradient into C_p; what its
    // affine part carries (VelocityTransfer::store_affine()) depends on the
    // point's second moment under the weights of the first step.
    prepare_transfer();
    const unsigned int n_points = point_properties.size();
    point_sum_D.assign(n_points, Tensor<2, dim>());
    unsigned int k = 0;
    for (const auto &cell : active_cells)
      for (unsigned int q = 0; q < cell.n_points; ++q, ++k)
        if (point_domains.enabled())
          point_sum_D[corner_point[k]] +=
            corner_alpha[k] *
            VelocityTransfer<dim>::second_moment(shape_functions[k].value,
                                                 corner_node_offsets(cell, k));
        else
          point_sum_D[k] = VelocityTransfer<dim>::second_moment(
            shape_functions[k].value, vertex_offsets(cell, shape_functions[k]));
    for (unsigned int p = 0; p < n_points; ++p)
      {
        double *affine = point_properties[p] + transfer_slot;
        VelocityTransfer<dim>::store_affine(
          VelocityTransfer<dim>::stored_affine(affine), point_sum_D[p], affine);
      }
  }


  template <int dim>
  void
  Simulator<dim>::prepare_transfer()
  {
    if (point_domains.enabled())
      return prepare_cpdi_transfer();
    TimerOutput::Scope t(timer, "shape functions");
    active_cells.clear();
    shape_functions.resize(particle_handler.n_locally_owned_particles());
    point_properties.resize(particle_handler.n_locally_owned_particles());
    active_dofs.clear();

    unsigned int k     = 0;
    double       h_min = std::numeric_limits<double>::max();
    for (auto it = particle_handler.begin(); it != particle_handler.end();)
      {
        const typename Triangulation<dim>::active_cell_iterator cell =
          it->get_surrounding_cell();
        const auto points = particle_handler.particles_in_cell(cell);
        h_min             = std::min(h_min, grid.cell_size(cell));
        // The number of points is counted below, in the loop over them
        // (ParticleHandler::n_particles_in_cell() looks the cell up again).
        ActiveCell active{0,
                          local_dofs_of_cells[cell->active_cell_index()],
                          &grid.cell_vertices(cell)};
        for (const auto &vertex_dofs : active.dofs)
          for (const unsigned int local : vertex_dofs)
            if (!dof_is_active[local])
              {
                dof_is_active[local] = 1;
                active_dofs.push_back(local);
              }
        if constexpr (dim == 2)
          active.map = &grid.bilinear_map(cell);
        const unsigned int first_point = k;

        // The cell's geometry as the shape functions take it: its bilinear
        // map in 2D, its vertices in 3D.
        const auto fill = [&](const auto &geometry) {
          for (auto point = points.begin(); point != points.end(); ++point)
            {
              point_properties[k] = point->get_properties().data();
              shape_functions[k++].reinit(geometry,
                                          point->get_reference_location());
            }
        };
        if constexpr (dim == 2)
          fill(*active.map);
        else
          fill(grid.cell_vertices(cell));
        active.n_points = k - first_point;
        active_cells.push_back(active);
        it = points.end();
      }
    for (const unsigned int i : active_dofs)
      dof_is_active[i] = 0;
    active_cell_size = Utilities::MPI::min(h_min, mpi_communicator);
  }


  template <int dim>
  void
  Simulator<dim>::map_mass_and_momentum(const bool with_forces)
  {
    if (point_domains.enabled())
      return map_mass_and_momentum_cpdi(with_forces);
    TimerOutput::Scope t(timer, "particle to grid");
    using Layout           = PropertyLayout<dim>;
    constexpr unsigned int n_vertices = GeometryInfo<dim>::vertices_per_cell;
    const Tensor<1, dim>   g          = time_stepping.gravity;
    const bool affine = transfer.scheme() == TransferScheme::apic;
    unsigned int           k          = 0;
    for (const auto &cell : active_cells)
      {
        // Summed over the cell's points first and added to the nodes once
        // per cell: added point by point, every point waited for the
        // previous point's load-add-store of the same nodal entries.
        std::array<Tensor<1, dim>, n_vertices> mass, momentum, forces;
        for (unsigned int q = 0; q < cell.n_points; ++q, ++k)
          {
            const double *props = point_properties[k];
            const double  m     = props[Layout::mass];
            const auto    v     = read_vector<dim>(&props[Layout::velocity]);
            const auto   &sf    = shape_functions[k];
            if (affine)
              {
                // APIC: each vertex receives the point's affine field
                // there, v_p + C_p (x_i - x_p).
                const auto dx = vertex_offsets(cell, sf);
                const auto C =
                  transfer.affine_matrix(sf, dx, props + transfer_slot);
                add_mass_and_momentum(sf.value, m, v, &C, &dx, mass, momentum);
              }
            else
              add_mass_and_momentum(
                sf.value, m, v, nullptr, nullptr, mass, momentum);
            if (with_forces)
              add_point_forces(props, sf, g, forces);
          }
        add_to_nodes(cell, mass, nodal_mass);
        add_to_nodes(cell, momentum, nodal_momentum);
        if (with_forces)
          add_to_nodes(cell, forces, nodal_force);
      }
    add_contributions_of_all_ranks(nodal_mass);
    add_contributions_of_all_ranks(nodal_momentum);
    if (with_forces)
      add_contributions_of_all_ranks(nodal_force);
  }


  template <int dim>
  void
  Simulator<dim>::filter_brought_velocity()
  {
    TimerOutput::Scope t(timer, "transfer filter");
    const auto        &coefficients = transfer.filter_coefficients();
    // u_1 = the constrained brought velocity (compute_nodal_velocity()).
    for (const unsigned int i : active_dofs)
      {
        const double u                     = nodal_velocity.local_element(i);
        round_trip_velocity.local_element(i) = u;
        filtered_velocity.local_element(i)   = coefficients[0] * u;
      }
    for (unsigned int k = 1; k < coefficients.size(); ++k)
      {
        // u_{k+1} = P S S+ u_k: interpolate to the points, project back
        // with their masses, constrain.
        if (point_domains.enabled())
          round_trip_cpdi();
        else
          round_trip();
        for (const unsigned int i : active_dofs)
          {
            const double m = nodal_mass.local_element(i);
            round_trip_velocity.local_element(i) =
              m > 0 ? round_trip_momentum.local_element(i) / m : 0.;
          }
        // The same projection as u_1's (compute_nodal_velocity()).
        boundary_conditions.project_velocity(
          round_trip_velocity,
          BoundaryConditions<dim>::Contact::as_last_update);
        for (const unsigned int i : active_dofs)
          filtered_velocity.local_element(i) +=
            coefficients[k] * round_trip_velocity.local_element(i);
      }
    // The nodal update starts from the brought velocity p / m: it is now
    // the filtered one, so friction and the walls act on it.
    for (const unsigned int i : active_dofs)
      nodal_momentum.local_element(i) =
        nodal_mass.local_element(i) * filtered_velocity.local_element(i);
  }


  template <int dim>
  void
  Simulator<dim>::round_trip()
  {
    constexpr unsigned int n_vertices = GeometryInfo<dim>::vertices_per_cell;
    using Layout                      = PropertyLayout<dim>;
    zero_touched_entries(round_trip_momentum);
    unsigned int p = 0;
    for (const auto &cell : active_cells)
      {
        std::array<Tensor<1, dim>, n_vertices> u_node, sums;
        for (unsigned int i = 0; i < n_vertices; ++i)
          for (unsigned int c = 0; c < dim; ++c)
            u_node[i][c] =
              round_trip_velocity.local_element(cell.dofs[i][c]);
        for (unsigned int q = 0; q < cell.n_points; ++q, ++p)
          {
            const auto    &N = shape_functions[p].value;
            Tensor<1, dim> v;
            for (unsigned int i = 0; i < n_vertices; ++i)
              v += N[i] * u_node[i];
            v *= point_properties[p][Layout::mass];
            for (unsigned int i = 0; i < n_vertices; ++i)
              sums[i] += N[i] * v;
          }
        add_to_nodes(cell, sums, round_trip_momentum);
      }
    add_contributions_of_all_ranks(round_trip_momentum);
  }


  template <int dim>
  inline void
  Simulator<dim>::add_point_forces(
    const double                *props,
    const Q1ShapeFunctions<dim> &sf,
    const Tensor<1, dim>        &g,
    std::array<Tensor<1, dim>, GeometryInfo<dim>::vertices_per_cell> &forces)
    const
  {
    using Layout   = PropertyLayout<dim>;
    const double m = props[Layout::mass];
    const double V = props[Layout::volume];
    // The dim x dim part of the stress: the only part that exerts in-plane
    // forces.
    const SymmetricTensor<2, 3> stress =
      read_symmetric_tensor(&props[Layout::stress]);
    Tensor<2, dim> sigma;
    for (unsigned int a = 0; a < dim; ++a)
      for (unsigned int b = 0; b < dim; ++b)
        sigma[a][b] = stress[a][b];
    for (unsigned int i = 0; i < sf.value.size(); ++i)
      forces[i] += -V * (sigma * sf.gradient[i]) + (sf.value[i] * m) * g;
  }


  template <int dim>
  void
  Simulator<dim>::map_forces()
  {
    if (point_domains.enabled())
      return map_forces_cpdi();
    TimerOutput::Scope t(timer, "particle to grid");
    const Tensor<1, dim> g = time_stepping.gravity;
    unsigned int         k = 0;
    for (const auto &cell : active_cells)
      {
        std::array<Tensor<1, dim>, GeometryInfo<dim>::vertices_per_cell>
          forces;
        for (unsigned int q = 0; q < cell.n_points; ++q, ++k)
          add_point_forces(point_properties[k], shape_functions[k], g, forces);
        add_to_nodes(cell, forces, nodal_force);
      }
    add_contributions_of_all_ranks(nodal_force);
  }


  template <int dim>
  void
  Simulator<dim>::update_points_from_grid(const bool remap_momentum)
  {
    if (point_domains.enabled())
      return update_points_from_grid_cpdi(remap_momentum);
    TimerOutput::Scope t(timer, "grid to particle");
    using Layout        = PropertyLayout<dim>;
    const bool   affine = transfer.scheme() == TransferScheme::apic;
    double       v_max2 = 0;
    auto         point  = particle_handler.begin();
    unsigned int k      = 0;
    if (remap_momentum)
      zero_touched_entries(nodal_momentum);
    constexpr unsigned int n_vertices = GeometryInfo<dim>::vertices_per_cell;
    for (const auto &cell : active_cells)
      {
        // The cell's nodal values, read once for all its points (through
        // the points' property pointers the compiler may not keep them in
        // registers), and the remapped momentum summed over its points and
        // added to the nodes once (see map_mass_and_momentum()).
        std::array<Tensor<1, dim>, n_vertices> a_node, v_node, remapped;
        for (unsigned int i = 0; i < n_vertices; ++i)
          for (unsigned int c = 0; c < dim; ++c)
            {
              a_node[i][c] = nodal_acceleration.local_element(cell.dofs[i][c]);
              v_node[i][c] = nodal_velocity_new.local_element(cell.dofs[i][c]);
            }
        for (unsigned int q = 0; q < cell.n_points; ++q, ++point, ++k)
        {
          const auto    &N = shape_functions[k].value;
          Tensor<1, dim> a, v_new;
          for (unsigned int i = 0; i < n_vertices; ++i)
            for (unsigned int c = 0; c < dim; ++c)
              {
                a[c] += N[i] * a_node[i][c];
                v_new[c] += N[i] * v_node[i][c];
              }
          double *props = point->get_properties().data();
          advance_point(point, props, a, v_new, cell.map, v_max2);
          // APIC: with MUSL the affine matrix is set by the stress update
          // (the gradient of the remapped velocity) and the remap below is
          // PIC's; with USF and USL it is B D^{-1} of the end-of-step grid
          // velocity (doc/transfers.md: exact, but unstable at CFL >= 0.1).
          if (affine && !remap_momentum)
            VelocityTransfer<dim>::update_affine(shape_functions[k],
                                                 vertex_offsets(cell,
                                                                shape_functions[k]),
                                                 v_node,
                                                 &props[transfer_slot]);
          if (remap_momentum)
            {
              const double m = props[Layout::mass];
              const auto   v = read_vector<dim>(&props[Layout::velocity]);
              for (unsigned int i = 0; i < n_vertices; ++i)
                for (unsigned int c = 0; c < dim; ++c)
                  remapped[i][c] += N[i] * m * v[c];
            }
        }
        if (remap_momentum)
          add_to_nodes(cell, remapped, nodal_momentum);
      }
    if (remap_momentum)
      {
        add_contributions_of_all_ranks(nodal_momentum);
      }
    set_max_point_speed(v_max2);
  }


  template <int dim>
  void
  Simulator<dim>::advance_point(
    typename Particles::ParticleHandler<dim>::particle_iterator point,
    double                                                           *props,
    const Tensor<1, dim>                                             &a,
    const Tensor<1, dim>                                             &v_new,
    const BilinearCellMap                                            *map,
    double                                                           &v_max2)
  {
    using Layout      = PropertyLayout<dim>;
    const double dt   = time_step;
    const double flip = transfer.flip_fraction();
    for (unsigned int c = 0; c < dim; ++c)
      {
        double &v = props[Layout::velocity + c];
        v         = flip * (v + dt * a[c]) + (1 - flip) * v_new[c];
      }
    // As one Tensor expression: built component by component, the new
    // position was stored as two scalars and read back as one 16-byte
    // value for set_location(), a store-forwarding stall that was a tenth
    // of this loop.
    const Point<dim> x = point->get_location() + dt * v_new;
    point->set_location(x);
    // Step 1 of the point location, with each new position at hand.
    if (point_relocation.can_locate_while_moving())
      point_relocation.locate_in_cell(*map, point, x);
    const double speed2 =
      read_vector<dim>(&props[Layout::velocity]).norm_square();
    v_max2 = std::max(v_max2, speed2);
    // Blow-up check at the price of one sum: a NaN or infinity in the
    // velocity, position or stress makes it non-finite.
    double check = speed2 + x[0] + x[dim - 1];
    for (unsigned int c = 0; c < 6; ++c)
      check += props[Layout::stress + c];
    if (!std::isfinite(check) && first_bad_point.empty())
      {
        std::ostringstream s;
        s << "material point " << point->get_id() << " at ("
          << point->get_location() << ") in cell "
          << point->get_surrounding_cell()->id().to_string()
          << " has a non-finite velocity, position or stress";
        first_bad_point = s.str();
      }
  }



#define MPM_INSTANTIATE(dim)                                                  \
  template void Simulator<dim>::prepare_transfer();                           \
  template void Simulator<dim>::map_mass_and_momentum(const bool);            \
  template void Simulator<dim>::filter_brought_velocity();                    \
  template void Simulator<dim>::round_trip();                                 \
  template void Simulator<dim>::map_forces();                                 \
  template void Simulator<dim>::update_points_from_grid(const bool);          \
  template void Simulator<dim>::advance_point(                                \
    typename Particles::ParticleHandler<dim>::particle_iterator,              \
    double *,                                                                 \
    const Tensor<1, dim> &,                                                   \
    const Tensor<1, dim> &,                                                   \
    const BilinearCellMap *,                                                  \
    double &);                                                                \
  template void Simulator<dim>::initialize_affine_matrices();
  MPM_INSTANTIATE(2)
  MPM_INSTANTIATE(3)
#undef MPM_INSTANTIATE
} // namespace MPM

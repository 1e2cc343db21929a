// The particle-grid passes with the mesh's own linear weights. The order
// of the passes is the Simulator's (Simulator::do_time_step()); the
// per-point arithmetic of the transfer schemes is in TransferScheme (APIC's in Apic), the
// point's own update in PointUpdate.

#include <deal.II/base/tensor.h>

#include <mpm/material_points/property_layout.h>
#include <mpm/transfer/linear_weights.h>

namespace MPM
{
  template <int dim>
  LinearWeights<dim>::LinearWeights(const TransferContext<dim> &context,
                                    ParameterHandler &)
    : ParticleGridWeights<dim>(context)
  {}


  template <int dim>
  double
  LinearWeights<dim>::prepare()
  {
    auto &particle_handler = this->context.particle_handler;
    const auto &grid       = this->context.grid;
    TimerOutput::Scope t(this->context.timer, "shape functions");
    this->clear_active_cells();
    this->shape_functions.resize(particle_handler.n_locally_owned_particles());
    this->points.resize(particle_handler.n_locally_owned_particles());

    unsigned int k = 0;
    for (auto it = particle_handler.begin(); it != particle_handler.end();)
      {
        const typename Triangulation<dim>::active_cell_iterator cell =
          it->get_surrounding_cell();
        const auto         points      = particle_handler.particles_in_cell(cell);
        const unsigned int first_point = k;
        // The cell's geometry as the shape functions take it: its bilinear
        // map in 2D, its vertices in 3D. The number of points is counted
        // here (ParticleHandler::n_particles_in_cell() looks the cell up
        // again).
        const auto fill = [&](const auto &geometry) {
          for (auto point = points.begin(); point != points.end(); ++point)
            {
              this->points[k] = point->get_properties().data();
              this->shape_functions[k++].reinit(
                geometry, point->get_reference_location());
            }
        };
        if constexpr (dim == 2)
          fill(grid.bilinear_map(cell));
        else
          fill(grid.cell_vertices(cell));
        this->add_active_cell(cell, k - first_point);
        it = points.end();
      }
    return this->finish_active_cells();
  }


  template <int dim>
  void
  LinearWeights<dim>::map_mass_and_momentum(const bool with_forces)
  {
    TimerOutput::Scope t(this->context.timer, "particle to grid");
    using Layout         = PropertyLayout<dim>;
    NodalFields   &nodal = this->context.nodal;
    const auto     g     = this->context.time_stepping.gravity;
    const bool     affine = this->affine();
    const auto    &transfer = this->context.transfer;
    unsigned int   k      = 0;
    for (const auto &cell : this->active_cells)
      {
        // Summed over the cell's points first and added to the nodes once
        // per cell: added point by point, every point waited for the
        // previous point's load-add-store of the same nodal entries.
        VertexValues mass, momentum, forces;
        for (unsigned int q = 0; q < cell.n_points; ++q, ++k)
          {
            const double *props = this->points[k];
            const double  m     = props[Layout::mass];
            const auto    v     = read_vector<dim>(&props[Layout::velocity]);
            const auto   &sf    = this->shape_functions[k];
            if (affine)
              {
                // APIC: each vertex receives the point's affine field
                // there, v_p + C_p (x_i - x_p).
                const auto dx = this->vertex_offsets(cell, sf);
                const auto C =
                  transfer.apic()->affine_matrix(sf, dx, props + this->transfer_slot);
                this->add_mass_and_momentum(
                  sf.value, m, v, &C, &dx, mass, momentum);
              }
            else
              this->add_mass_and_momentum(
                sf.value, m, v, nullptr, nullptr, mass, momentum);
            if (with_forces)
              add_point_forces(props, sf, g, forces);
          }
        this->add_to_nodes(cell, mass, nodal.mass);
        this->add_to_nodes(cell, momentum, nodal.momentum);
        if (with_forces)
          this->add_to_nodes(cell, forces, nodal.force);
      }
    this->add_contributions_of_all_ranks(nodal.mass);
    this->add_contributions_of_all_ranks(nodal.momentum);
    if (with_forces)
      this->add_contributions_of_all_ranks(nodal.force);
  }


  template <int dim>
  void
  LinearWeights<dim>::add_point_forces(const double                *props,
                                       const Q1ShapeFunctions<dim> &sf,
                                       const Tensor<1, dim>        &g,
                                       VertexValues                &forces)
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
    for (unsigned int i = 0; i < n_vertices; ++i)
      forces[i] += -V * (sigma * sf.gradient[i]) + (sf.value[i] * m) * g;
  }


  template <int dim>
  void
  LinearWeights<dim>::map_forces()
  {
    TimerOutput::Scope t(this->context.timer, "particle to grid");
    const auto         g = this->context.time_stepping.gravity;
    unsigned int       k = 0;
    for (const auto &cell : this->active_cells)
      {
        VertexValues forces;
        for (unsigned int q = 0; q < cell.n_points; ++q, ++k)
          add_point_forces(this->points[k], this->shape_functions[k], g, forces);
        this->add_to_nodes(cell, forces, this->context.nodal.force);
      }
    this->add_contributions_of_all_ranks(this->context.nodal.force);
  }


  template <int dim>
  double
  LinearWeights<dim>::update_points_from_grid(const bool remap_momentum)
  {
    TimerOutput::Scope t(this->context.timer, "grid to particle");
    using Layout          = PropertyLayout<dim>;
    NodalFields &nodal    = this->context.nodal;
    auto        &updater  = this->context.point_update;
    const bool   affine   = this->affine();
    double       v_max2   = 0;
    auto         point    = this->context.particle_handler.begin();
    unsigned int k        = 0;
    if (remap_momentum)
      this->zero_touched_entries(nodal.momentum);
    for (const auto &cell : this->active_cells)
      {
        // The cell's nodal values, read once for all its points (through
        // the points' property pointers the compiler may not keep them in
        // registers), and the remapped momentum summed over its points and
        // added to the nodes once (see map_mass_and_momentum()).
        const VertexValues a_node = this->read_nodes(cell, nodal.acceleration);
        const VertexValues v_node = this->read_nodes(cell, nodal.velocity_new);
        VertexValues       remapped;
        for (unsigned int q = 0; q < cell.n_points; ++q, ++point, ++k)
          {
            const auto    &N = this->shape_functions[k].value;
            Tensor<1, dim> a, v_new;
            for (unsigned int i = 0; i < n_vertices; ++i)
              for (unsigned int c = 0; c < dim; ++c)
                {
                  a[c] += N[i] * a_node[i][c];
                  v_new[c] += N[i] * v_node[i][c];
                }
            double *props = point->get_properties().data();
            updater.advance(point, props, a, v_new, cell.map, v_max2);
            // APIC: with MUSL the affine matrix is set by the stress update
            // (the gradient of the remapped velocity) and the remap below
            // is PIC's; with USF and USL it is B D^{-1} of the end-of-step
            // grid velocity (doc/transfers.md: exact, but unstable at
            // CFL >= 0.1).
            if (affine && !remap_momentum)
              Apic<dim>::update_affine(
                this->shape_functions[k],
                this->vertex_offsets(cell, this->shape_functions[k]),
                v_node,
                &props[this->transfer_slot]);
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
          this->add_to_nodes(cell, remapped, nodal.momentum);
      }
    if (remap_momentum)
      this->add_contributions_of_all_ranks(nodal.momentum);
    return v_max2;
  }


  template <int dim>
  void
  LinearWeights<dim>::update_stress(const NodalVector &velocity,
                                    const bool         set_affine)
  {
    TimerOutput::Scope t(this->context.timer, "stress update");
    const auto &updater = this->context.point_update;
    const bool  average = updater.averages_volumetric_strain();
    // sum_i v_i (x) grad N_i at a point with shape functions sf.
    const auto velocity_gradient = [](const VertexValues          &v_node,
                                      const Q1ShapeFunctions<dim> &sf) {
      Tensor<2, dim> grad_v;
      for (unsigned int i = 0; i < n_vertices; ++i)
        grad_v += outer_product(v_node[i], sf.gradient[i]);
      return grad_v;
    };
    unsigned int k = 0;
    for (const auto &cell : this->active_cells)
      {
        const VertexValues v_node = this->read_nodes(cell, velocity);
        // With 'Volumetric strain averaging = cell', the cell's velocity
        // gradients first, to average their traces.
        if (average)
          {
            cell_gradients.resize(cell.n_points);
            for (unsigned int q = 0; q < cell.n_points; ++q)
              cell_gradients[q] =
                velocity_gradient(v_node, this->shape_functions[k + q]);
            PointUpdate<dim>::average_volumetric_part(this->points.data() + k,
                                                      cell_gradients.data(),
                                                      cell.n_points);
          }
        for (unsigned int q = 0; q < cell.n_points; ++q, ++k)
          {
            const auto          &sf     = this->shape_functions[k];
            const Tensor<2, dim> grad_v = average ?
                                            cell_gradients[q] :
                                            velocity_gradient(v_node, sf);
            double *props = this->points[k];
            updater.update_stress(props, grad_v);
            // MUSL with APIC: the affine matrix is this velocity gradient
            // (see Apic::store_affine()).
            if (set_affine)
              Apic<dim>::store_affine(
                grad_v,
                Apic<dim>::second_moment(
                  sf.value, this->vertex_offsets(cell, sf)),
                props + this->transfer_slot);
          }
      }
  }


  template <int dim>
  void
  LinearWeights<dim>::round_trip(const NodalVector &velocity,
                                 NodalVector       &momentum)
  {
    using Layout = PropertyLayout<dim>;
    this->zero_touched_entries(momentum);
    unsigned int p = 0;
    for (const auto &cell : this->active_cells)
      {
        const VertexValues u_node = this->read_nodes(cell, velocity);
        VertexValues       sums;
        for (unsigned int q = 0; q < cell.n_points; ++q, ++p)
          {
            const auto    &N = this->shape_functions[p].value;
            Tensor<1, dim> v;
            for (unsigned int i = 0; i < n_vertices; ++i)
              v += N[i] * u_node[i];
            v *= this->points[p][Layout::mass];
            for (unsigned int i = 0; i < n_vertices; ++i)
              sums[i] += N[i] * v;
          }
        this->add_to_nodes(cell, sums, momentum);
      }
    this->add_contributions_of_all_ranks(momentum);
  }


  template <int dim>
  void
  LinearWeights<dim>::second_moments(std::vector<Tensor<2, dim>> &D) const
  {
    D.resize(this->points.size());
    unsigned int k = 0;
    for (const auto &cell : this->active_cells)
      for (unsigned int q = 0; q < cell.n_points; ++q, ++k)
        D[k] = Apic<dim>::second_moment(
          this->shape_functions[k].value,
          this->vertex_offsets(cell, this->shape_functions[k]));
  }


  template class LinearWeights<2>;
  template class LinearWeights<3>;
} // namespace MPM

MPM_REGISTER_PARTICLE_GRID_WEIGHTS(MPM::LinearWeights,
                                   "linear",
                                   "the mesh's bilinear functions at the point.")

#ifndef mpm_transfer_particle_grid_passes_templates_h
#define mpm_transfer_particle_grid_passes_templates_h

// The bodies of ParticleGridPasses, included by each weight function's
// source file, which instantiates them with its own hooks (inlined).

#include <mpm/material_points/property_layout.h>
#include <mpm/parallel/thread_chunks.h>
#include <mpm/transfer/apic.h>
#include <mpm/transfer/particle_grid_passes.h>

namespace MPM
{
  template <int dim, class Weights>
  template <std::size_t n_targets, typename Body>
  void
  ParticleGridPasses<dim, Weights>::for_active_cells(
    const std::array<NodalVector *, n_targets> &targets,
    const Body                                 &body)
  {
    // A node whose cells all lie in one chunk receives their sums from
    // that chunk's thread, in the order of the cells; a node of cells of
    // several chunks receives them all after the threaded loop, in the
    // order of the cells. Either way the order of one thread.
    const unsigned int n_cells    = this->active_cells.size();
    const unsigned int chunk_size = this->cell_chunk_size;
    // Grown only: value-initialising it again at every size change (the
    // passes have 1 to 3 targets) would cost a write of the whole array.
    const std::size_t n_sums =
      this->cells_on_chunk_borders.size() * n_targets;
    if (cell_sums.size() < n_sums)
      cell_sums.resize(n_sums);
    for_each_chunk(
      n_cells,
      chunk_size,
      [&](const unsigned int chunk,
          const unsigned int first,
          const unsigned int last) {
        // Zero once here, and each target's sums again after they are
        // handed on: zeroing all of them at the start of every cell
        // compiled to a 'rep stos' (7 % of the 2D particle-to-grid pass).
        std::array<VertexValues, n_targets> sums;
        for (unsigned int c = first; c < last; ++c)
          {
            body(c, chunk, sums);
            const ActiveCell   &cell   = this->active_cells[c];
            const unsigned char shared = cell.vertices_shared_with_other_chunks;
            for (unsigned int f = 0; f < n_targets; ++f)
              {
                if (targets[f] != nullptr)
                  {
                    if (shared == 0)
                      this->add_to_nodes(cell, sums[f], *targets[f]);
                    else
                      {
                        for (unsigned int i = 0; i < n_vertices; ++i)
                          if ((shared & (1u << i)) == 0)
                            for (unsigned int d = 0; d < dim; ++d)
                              targets[f]->local_element(cell.dofs[i][d]) +=
                                sums[f][i][d];
                        cell_sums[std::size_t(cell.border_index) *
                                    n_targets +
                                  f] = sums[f];
                      }
                  }
                sums[f] = VertexValues();
              }
          }
      });
    for (std::size_t b = 0; b < this->cells_on_chunk_borders.size(); ++b)
      {
        const ActiveCell &cell =
          this->active_cells[this->cells_on_chunk_borders[b]];
        for (unsigned int f = 0; f < n_targets; ++f)
          if (targets[f] != nullptr)
            for (unsigned int i = 0; i < n_vertices; ++i)
              if ((cell.vertices_shared_with_other_chunks & (1u << i)) != 0)
                for (unsigned int d = 0; d < dim; ++d)
                  targets[f]->local_element(cell.dofs[i][d]) +=
                    cell_sums[b * n_targets + f][i][d];
      }
  }


  template <int dim, class Weights>
  template <typename Body>
  void
  ParticleGridPasses<dim, Weights>::for_point_cells(const Body &body)
  {
    const unsigned int n_point_cells =
      point_cell_begin.empty() ? 0 : point_cell_begin.size() - 1;
    chunk_findings.resize(chunk_count(n_point_cells, this->cell_chunk_size));
    for_each_chunk(n_point_cells,
                   this->cell_chunk_size,
                   [&](const unsigned int chunk,
                       const unsigned int first,
                       const unsigned int last) {
                     for (unsigned int c = first; c < last; ++c)
                       body(c, chunk);
                   });
  }


  template <int dim, class Weights>
  double
  ParticleGridPasses<dim, Weights>::record_chunk_findings()
  {
    double v_max2 = 0;
    for (auto &findings : chunk_findings)
      v_max2 = std::max(v_max2, this->get_point_update().record(findings));
    return v_max2;
  }


  template <int dim, class Weights>
  void
  ParticleGridPasses<dim, Weights>::map_mass_and_momentum(
    const bool with_forces)
  {
    TimerOutput::Scope t(this->get_timer(), "particle to grid");
    using Layout               = PropertyLayout<dim>;
    NodalFields         &nodal = this->get_nodal_fields();
    const Tensor<1, dim> g     = this->get_time_stepping().gravity;
    const Apic<dim>     *apic  = this->get_transfer().apic();
    if (!Weights::entries_are_points)
      gather_point_transfer_data(with_forces);
    if (apic != nullptr && !Weights::entries_are_points)
      {
        // APIC: each point's affine matrix at its weights of this step
        // (Apic::affine_matrix()), which needs its second moment D_p summed
        // over its entries first.
        const unsigned int n_points = this->points.size();
        second_moments(point_second_moment);
        point_affine.resize(n_points);
        for (unsigned int p = 0; p < n_points; ++p)
          point_affine[p] = apic->affine_matrix(this->points[p] +
                                                  this->transfer_slot,
                                                point_second_moment[p]);
      }
    // Summed over each cell's entries first and added to the nodes once
    // per cell: added entry by entry, every entry waited for the previous
    // one's load-add-store of the same nodal entries.
    this->template for_active_cells<3>(
      {{&nodal.mass, &nodal.momentum, with_forces ? &nodal.force : nullptr}},
      [&](const unsigned int c,
          const unsigned int,
          std::array<VertexValues, 3> &sums) {
        const ActiveCell &cell     = this->active_cells[c];
        VertexValues     &mass     = sums[0];
        VertexValues     &momentum = sums[1];
        VertexValues     &forces   = sums[2];
        const unsigned int end     = cell.first_entry + cell.n_points;
        for (unsigned int k = cell.first_entry; k < end; ++k)
          {
            const unsigned int p     = weights().point_of_entry(k);
            const double      *props = this->points[p];
            const double       m     = Weights::entries_are_points ?
                                         props[Layout::mass] :
                                         point_transfer_data[p].mass;
            const Tensor<1, dim> v =
              Weights::entries_are_points ?
                read_vector<dim>(&props[Layout::velocity]) :
                point_transfer_data[p].velocity;
            const auto &sf = this->shape_functions[k];
            if (apic != nullptr)
              {
                // Each vertex receives the point's affine field there,
                // v_p + C_p (x_i - xbar_p).
                const VertexValues dx = weights().node_offsets(cell, k);
                Tensor<2, dim>     C;
                if constexpr (Weights::entries_are_points)
                  C = apic->affine_matrix(sf, dx, props + this->transfer_slot);
                else
                  C = point_affine[p];
                this->add_mass_and_momentum(
                  sf.value, m, v, &C, &dx, mass, momentum);
              }
            else
              this->add_mass_and_momentum(
                sf.value, m, v, nullptr, nullptr, mass, momentum);
            if (with_forces)
              {
                if constexpr (Weights::entries_are_points)
                  add_entry_forces(k,
                                   m,
                                   props[Layout::volume],
                                   PointTransferData::in_plane_stress(props),
                                   g,
                                   forces);
                else
                  add_entry_forces(k,
                                   m,
                                   point_transfer_data[p].volume,
                                   point_transfer_data[p].stress,
                                   g,
                                   forces);
              }
          }
      });
    this->add_contributions_of_all_ranks(nodal.mass);
    this->add_contributions_of_all_ranks(nodal.momentum);
    if (with_forces)
      this->add_contributions_of_all_ranks(nodal.force);
  }


  template <int dim, class Weights>
  void
  ParticleGridPasses<dim, Weights>::map_forces()
  {
    TimerOutput::Scope t(this->get_timer(), "particle to grid");
    using Layout           = PropertyLayout<dim>;
    const Tensor<1, dim> g = this->get_time_stepping().gravity;
    if (!Weights::entries_are_points)
      gather_point_transfer_data(true);
    this->template for_active_cells<1>(
      {{&this->get_nodal_fields().force}},
      [&](const unsigned int c,
          const unsigned int,
          std::array<VertexValues, 1> &forces) {
        const ActiveCell  &cell = this->active_cells[c];
        const unsigned int end  = cell.first_entry + cell.n_points;
        for (unsigned int k = cell.first_entry; k < end; ++k)
          if constexpr (Weights::entries_are_points)
            {
              const double *props = this->points[k];
              add_entry_forces(k,
                               props[Layout::mass],
                               props[Layout::volume],
                               PointTransferData::in_plane_stress(props),
                               g,
                               forces[0]);
            }
          else
            {
              const PointTransferData &point =
                point_transfer_data[weights().point_of_entry(k)];
              add_entry_forces(
                k, point.mass, point.volume, point.stress, g, forces[0]);
            }
      });
    this->add_contributions_of_all_ranks(this->get_nodal_fields().force);
  }


  template <int dim, class Weights>
  void
  ParticleGridPasses<dim, Weights>::add_entry_forces(
    const unsigned int    k,
    const double          m,
    const double          V,
    const Tensor<2, dim> &sigma,
    const Tensor<1, dim> &g,
    VertexValues         &forces) const
  {
    const auto &sf = this->shape_functions[k];
    for (unsigned int i = 0; i < n_vertices; ++i)
      forces[i] += -V * (sigma * sf.gradient[i]) + (sf.value[i] * m) * g;
  }


  template <int dim, class Weights>
  Tensor<2, dim>
  ParticleGridPasses<dim, Weights>::PointTransferData::in_plane_stress(
    const double *props)
  {
    using Layout = PropertyLayout<dim>;
    // The dim x dim part of the stress: the only part that exerts in-plane
    // forces.
    const SymmetricTensor<2, 3> stress =
      read_symmetric_tensor(&props[Layout::stress]);
    Tensor<2, dim> sigma;
    for (unsigned int a = 0; a < dim; ++a)
      for (unsigned int b = 0; b < dim; ++b)
        sigma[a][b] = stress[a][b];
    return sigma;
  }


  template <int dim, class Weights>
  typename ParticleGridPasses<dim, Weights>::PointTransferData
  ParticleGridPasses<dim, Weights>::PointTransferData::read(
    const double *props,
    const bool    with_stress)
  {
    using Layout = PropertyLayout<dim>;
    PointTransferData point;
    point.mass     = props[Layout::mass];
    point.velocity = read_vector<dim>(&props[Layout::velocity]);
    point.volume   = with_stress ? props[Layout::volume] : 0.;
    if (with_stress)
      point.stress = in_plane_stress(props);
    return point;
  }


  template <int dim, class Weights>
  void
  ParticleGridPasses<dim, Weights>::gather_point_transfer_data(
    const bool with_stress)
  {
    const unsigned int n_points = this->points.size();
    point_transfer_data.resize(n_points);
    for_each_chunk(n_points,
                   chunk_size_for(n_points),
                   [&](const unsigned int,
                       const unsigned int first,
                       const unsigned int last) {
                     for (unsigned int p = first; p < last; ++p)
                       point_transfer_data[p] =
                         PointTransferData::read(this->points[p], with_stress);
                   });
  }


  template <int dim, class Weights>
  void
  ParticleGridPasses<dim, Weights>::add_to_affine_fit(
    const ActiveCell   &cell,
    const unsigned int  k,
    const VertexValues &v_node,
    AffineFitSums      &sums) const
  {
    const auto        &N  = this->shape_functions[k].value;
    const VertexValues dx = weights().node_offsets(cell, k);
    for (unsigned int i = 0; i < n_vertices; ++i)
      {
        const Tensor<1, dim> w_dx = N[i] * dx[i];
        sums.B += outer_product(v_node[i], w_dx);
        sums.D += outer_product(w_dx, dx[i]);
        sums.node_scale = std::max(sums.node_scale, dx[i].norm_square());
      }
    sums.gradient += entry_velocity_gradient(k, v_node);
  }


  template <int dim, class Weights>
  double
  ParticleGridPasses<dim, Weights>::update_points_from_grid(
    const bool remap_momentum)
  {
    TimerOutput::Scope t(this->get_timer(), "grid to particle");
    using Layout           = PropertyLayout<dim>;
    NodalFields &nodal     = this->get_nodal_fields();
    auto        &updater   = this->get_point_update();
    // APIC: the new C_p is fitted here, except under MUSL where a point's
    // second moment can vanish (linear weights; a shrunk CPDI domain,
    // Weights::fit_is_stable()): there it is the gradient of the remapped
    // velocity (update_stress()) and the point's remap below is PIC's.
    const bool fit_affine = this->affine();
    const auto fits       = [&](const double *props) {
      return fit_affine && (!remap_momentum || weights().fit_is_stable(props));
    };
    // The momentum (v_p + C_p dx_i) m_p w_ip a point maps back under MUSL,
    // into the per-vertex sums @p remapped of entry k's cell.
    // (Where the entries are not the points, from point_transfer_data,
    // copied in the points' update.)
    const auto remap = [&](const ActiveCell    &cell,
                           const unsigned int   k,
                           const Tensor<2, dim> *C,
                           VertexValues        &remapped) {
      const unsigned int   p  = weights().point_of_entry(k);
      const double         m  = Weights::entries_are_points ?
                                  this->points[p][Layout::mass] :
                                  point_transfer_data[p].mass;
      const Tensor<1, dim> v  = Weights::entries_are_points ?
                                  read_vector<dim>(
                                    &this->points[p][Layout::velocity]) :
                                  point_transfer_data[p].velocity;
      const auto          &N  = this->shape_functions[k].value;
      if (C != nullptr)
        {
          const VertexValues dx = weights().node_offsets(cell, k);
          for (unsigned int i = 0; i < n_vertices; ++i)
            remapped[i] += (N[i] * m) * (v + *C * dx[i]);
        }
      else
        for (unsigned int i = 0; i < n_vertices; ++i)
          remapped[i] += (N[i] * m) * v;
    };
    double v_max2 = 0;
    if constexpr (Weights::entries_are_points)
      {
        // Each point finished in its cell's loop: the cell's nodal values
        // read once for all its points (through the points' property
        // pointers the compiler may not keep them in registers).
        if (remap_momentum)
          this->zero_touched_entries(nodal.momentum);
        chunk_findings.resize(
          chunk_count(this->active_cells.size(), this->cell_chunk_size));
        this->template for_active_cells<1>(
          {{remap_momentum ? &nodal.momentum : nullptr}},
          [&](const unsigned int c,
              const unsigned int chunk,
              std::array<VertexValues, 1> &remapped) {
            const ActiveCell  &cell = this->active_cells[c];
            const VertexValues a_node =
              this->read_nodes(cell, nodal.acceleration);
            const VertexValues v_node =
              this->read_nodes(cell, nodal.velocity_new);
            auto               point = cell.first_point;
            const unsigned int end   = cell.first_entry + cell.n_points;
            for (unsigned int k = cell.first_entry; k < end; ++k, ++point)
              {
                const auto    &N = this->shape_functions[k].value;
                Tensor<1, dim> a, v_new;
                for (unsigned int i = 0; i < n_vertices; ++i)
                  {
                    a += N[i] * a_node[i];
                    v_new += N[i] * v_node[i];
                  }
                double *props = this->points[k];
                updater.advance(
                  point, props, a, v_new, cell.map, chunk_findings[chunk]);
                Tensor<2, dim> C;
                const bool     fitted = fits(props);
                if (fitted)
                  {
                    AffineFitSums sums;
                    add_to_affine_fit(cell, k, v_node, sums);
                    C = Apic<dim>::fit_affine(sums.B,
                                              sums.D,
                                              sums.gradient,
                                              sums.node_scale,
                                              props + this->transfer_slot);
                  }
                if (remap_momentum)
                  remap(cell, k, fitted ? &C : nullptr, remapped[0]);
              }
          });
        v_max2 = record_chunk_findings();
      }
    else
      {
        // 1. Each point's acceleration and velocity, summed over its
        //    entries (and, with APIC, the sums of its fit): one thread,
        //    since a point's entries lie in several cells.
        const unsigned int n_points = this->points.size();
        point_sum_a.assign(n_points, Tensor<1, dim>());
        point_sum_v.assign(n_points, Tensor<1, dim>());
        if (fit_affine)
          point_affine_fit.assign(n_points, AffineFitSums());
        for (const auto &cell : this->active_cells)
          {
            const VertexValues a_node =
              this->read_nodes(cell, nodal.acceleration);
            const VertexValues v_node =
              this->read_nodes(cell, nodal.velocity_new);
            const unsigned int end = cell.first_entry + cell.n_points;
            for (unsigned int k = cell.first_entry; k < end; ++k)
              {
                const auto    &N = this->shape_functions[k].value;
                Tensor<1, dim> a, v;
                for (unsigned int i = 0; i < n_vertices; ++i)
                  {
                    a += N[i] * a_node[i];
                    v += N[i] * v_node[i];
                  }
                const unsigned int p = weights().point_of_entry(k);
                point_sum_a[p] += a;
                point_sum_v[p] += v;
                if (fit_affine)
                  add_to_affine_fit(cell, k, v_node, point_affine_fit[p]);
              }
          }
        // 2. The points, in chunks of their own cells (point_cell_begin),
        //    what they find taken over in chunk order; under MUSL each
        //    point's new velocity copied for the remap while its record is
        //    at hand (gather_point_transfer_data()'s copy, without a second
        //    pass over the records).
        if (fit_affine)
          {
            point_affine.resize(n_points);
            point_fitted.resize(n_points);
          }
        if (remap_momentum)
          point_transfer_data.resize(n_points);
        for_point_cells([&](const unsigned int c, const unsigned int chunk) {
          auto point = point_cell_first_point[c];
          for (unsigned int p = point_cell_begin[c];
               p < point_cell_begin[c + 1];
               ++p, ++point)
            {
              updater.advance(point,
                              this->points[p],
                              point_sum_a[p],
                              point_sum_v[p],
                              weights().cell_map_of_point(p),
                              chunk_findings[chunk]);
              const bool fitted = fits(this->points[p]);
              if (fit_affine)
                point_fitted[p] = fitted;
              if (fitted)
                {
                  const AffineFitSums &sums = point_affine_fit[p];
                  point_affine[p] =
                    Apic<dim>::fit_affine(sums.B,
                                          sums.D,
                                          sums.gradient,
                                          sums.node_scale,
                                          this->points[p] + this->transfer_slot);
                }
              if (remap_momentum)
                point_transfer_data[p] =
                  PointTransferData::read(this->points[p], false);
            }
        });
        v_max2 = record_chunk_findings();
        // 3. MUSL: the points' new momentum back to the nodes (whether a
        //    point was fitted read from point_fitted: reading it from the
        //    point's properties, scattered in memory, stalled this loop
        //    on every entry).
        if (remap_momentum)
          {
            this->zero_touched_entries(nodal.momentum);
            this->template for_active_cells<1>(
              {{&nodal.momentum}},
              [&](const unsigned int c,
                  const unsigned int,
                  std::array<VertexValues, 1> &remapped) {
                const ActiveCell  &cell = this->active_cells[c];
                const unsigned int end  = cell.first_entry + cell.n_points;
                for (unsigned int k = cell.first_entry; k < end; ++k)
                  {
                    const unsigned int p = weights().point_of_entry(k);
                    remap(cell,
                          k,
                          fit_affine && point_fitted[p] ? &point_affine[p] :
                                                          nullptr,
                          remapped[0]);
                  }
              });
          }
      }
    if (remap_momentum)
      this->add_contributions_of_all_ranks(nodal.momentum);
    return v_max2;
  }


  template <int dim, class Weights>
  template <typename RateOf>
  void
  ParticleGridPasses<dim, Weights>::patch_mean_rates_over_point_cells(
    const RateOf &rate_of)
  {
    if constexpr (Weights::entries_are_points)
      patch_mean_rates(
        this->active_cells.size(),
        [this](const unsigned int c) {
          const ActiveCell &cell = this->active_cells[c];
          return std::make_pair(cell.first_entry,
                                cell.first_entry + cell.n_points);
        },
        [this](const unsigned int c) -> const auto & {
          return this->active_cells[c].dofs;
        },
        rate_of);
    else
      patch_mean_rates(
        point_cell_begin.empty() ? 0 : point_cell_begin.size() - 1,
        [this](const unsigned int c) {
          return std::make_pair(point_cell_begin[c], point_cell_begin[c + 1]);
        },
        [this](const unsigned int c) -> const auto & {
          return this->get_cell_dofs()[point_cell_first_point[c]
                                         ->get_surrounding_cell()
                                         ->active_cell_index()];
        },
        rate_of);
  }



  template <int dim, class Weights>
  template <typename PointsOf, typename DofsOf, typename RateOf>
  void
  ParticleGridPasses<dim, Weights>::patch_mean_rates(const unsigned int n_cells,
                                                     const PointsOf &points_of,
                                                     const DofsOf   &dofs_of,
                                                     const RateOf   &rate_of)
  {
    // Each cell's vertex entries, looked up once.
    patch_cell_dofs.resize(n_cells);
    for (unsigned int c = 0; c < n_cells; ++c)
      patch_cell_dofs[c] = &dofs_of(c);
    // The cells' sums: components 0 and 1 of a vertex's entries will hold
    // sum V tr and sum V over the cells around it.
    cell_rate_sums.assign(n_cells, {{0., 0.}});
    for (unsigned int c = 0; c < n_cells; ++c)
      {
        const auto [begin, end] = points_of(c);
        for (unsigned int p = begin; p < end; ++p)
          {
            const auto [rate, weight] = rate_of(p);
            cell_rate_sums[c][0] += weight * rate;
            cell_rate_sums[c][1] += weight;
          }
      }
    const NodalVector &mass = this->get_nodal_fields().mass;
    if (patch_sums.get_partitioner() != mass.get_partitioner())
      patch_sums.reinit(mass.get_partitioner());
    // Zero what is read below and what compress() adds to: the entries of
    // these cells' vertices (with their periodic copies), the owned
    // entries of other ranks' ghosts, the ghosts.
    const auto zero = [this](const unsigned int i) {
      patch_sums.local_element(i) = 0;
    };
    for (const VertexDofs *dofs : patch_cell_dofs)
      for (const auto &vertex_dofs : *dofs)
        for (unsigned int k = 0; k < 2; ++k)
          {
            zero(vertex_dofs[k]);
            this->get_periodic_nodes().for_each_copy(vertex_dofs[k], zero);
          }
    for (const auto &range : patch_sums.get_partitioner()->import_indices())
      for (unsigned int i = range.first; i < range.second; ++i)
        zero(i);
    patch_sums.zero_out_ghost_values();
    for (unsigned int c = 0; c < n_cells; ++c)
      for (const auto &vertex_dofs : *patch_cell_dofs[c])
        {
          patch_sums.local_element(vertex_dofs[0]) += cell_rate_sums[c][0];
          patch_sums.local_element(vertex_dofs[1]) += cell_rate_sums[c][1];
        }
    this->add_contributions_of_all_ranks(patch_sums);
    cell_patch_means.assign(n_cells, 0.);
    for (unsigned int c = 0; c < n_cells; ++c)
      if (cell_rate_sums[c][1] > 0)
        {
          double mean = 0;
          for (const auto &vertex_dofs : *patch_cell_dofs[c])
            mean += patch_sums.local_element(vertex_dofs[0]) /
                    patch_sums.local_element(vertex_dofs[1]);
          cell_patch_means[c] = mean / n_vertices;
        }
  }


  template <int dim, class Weights>
  void
  ParticleGridPasses<dim, Weights>::update_stress(const NodalVector &velocity,
                                                  const bool set_affine)
  {
    TimerOutput::Scope t(this->get_timer(), "stress update");
    const auto        &updater = this->get_point_update();
    const bool         average = updater.averages_volumetric_strain();
    const bool patch = updater.averages_volumetric_strain_over_patches();
    // 'patch': point p's volumetric rate and its weight, its volume.
    const auto volume_weighted_trace = [this](const unsigned int p) {
      return std::make_pair(trace(point_gradients[p]),
                            this->points[p][PropertyLayout<dim>::volume]);
    };
    // MUSL with APIC, at the points whose C_p update_points_from_grid()
    // did not fit (Weights::fit_is_stable()): it is this velocity gradient
    // (Apic::store_affine()).
    const auto store_gradient = [&](const double *props) {
      return set_affine && !weights().fit_is_stable(props);
    };
    // Entry k's velocity gradient (nodal values @p v_node of its cell).
    const auto entry_gradient = [this](const unsigned int  k,
                                       const VertexValues &v_node) {
      return entry_velocity_gradient(k, v_node);
    };
    // The stress, volume and weights' own data of point p from its
    // gradient.
    const auto update_point = [&](const unsigned int    p,
                                  const Tensor<2, dim> &grad_v,
                                  const Tensor<2, dim> &D,
                                  const double          cell_size,
                                  typename PointUpdate<dim>::Findings &found) {
      double *props = this->points[p];
      const double volume_factor =
        updater.update_stress(props, grad_v, cell_size, found);
      const bool gradient_is_affine = store_gradient(props);
      weights().deform_with_point(p, props, grad_v, volume_factor);
      if (gradient_is_affine)
        Apic<dim>::store_affine(grad_v, D, props + this->transfer_slot);
    };
    if constexpr (Weights::entries_are_points)
      {
        const unsigned int n_chunks =
          chunk_count(this->active_cells.size(), this->cell_chunk_size);
        chunk_findings.resize(n_chunks);
        if (average)
          chunk_gradients.resize(n_chunks);
        if (patch)
          {
            // The points' velocity gradients first (kept for the stress
            // below), and from them the cells' and vertices' means.
            point_gradients.resize(this->points.size());
            this->template for_active_cells<0>(
              {},
              [&](const unsigned int c,
                  const unsigned int,
                  std::array<VertexValues, 0> &) {
                const ActiveCell  &cell   = this->active_cells[c];
                const VertexValues v_node = this->read_nodes(cell, velocity);
                const unsigned int end    = cell.first_entry + cell.n_points;
                for (unsigned int k = cell.first_entry; k < end; ++k)
                  point_gradients[k] = entry_gradient(k, v_node);
              });
            patch_mean_rates_over_point_cells(volume_weighted_trace);
          }
        this->template for_active_cells<0>(
          {},
          [&](const unsigned int c,
              const unsigned int chunk,
              std::array<VertexValues, 0> &) {
            const ActiveCell  &cell   = this->active_cells[c];
            const unsigned int k0     = cell.first_entry;
            const VertexValues v_node = this->read_nodes(cell, velocity);
            // With 'Volumetric strain averaging = cell', the cell's
            // velocity gradients first, to average their traces.
            // With 'patch', the gradients computed above.
            Tensor<2, dim> *gradients = nullptr;
            if (patch)
              {
                gradients = point_gradients.data() + k0;
                PointUpdate<dim>::set_volumetric_part(gradients,
                                                      cell.n_points,
                                                      cell_patch_means[c]);
              }
            else if (average)
              {
                std::vector<Tensor<2, dim>> &cell_gradients =
                  chunk_gradients[chunk];
                cell_gradients.resize(cell.n_points);
                for (unsigned int q = 0; q < cell.n_points; ++q)
                  cell_gradients[q] = entry_gradient(k0 + q, v_node);
                gradients = cell_gradients.data();
                PointUpdate<dim>::average_volumetric_part(
                  this->points.data() + k0, gradients, cell.n_points);
              }
            for (unsigned int q = 0; q < cell.n_points; ++q)
              {
                const unsigned int k = k0 + q;
                update_point(
                  k,
                  gradients ? gradients[q] : entry_gradient(k, v_node),
                  store_gradient(this->points[k]) ?
                    Apic<dim>::second_moment(this->shape_functions[k].value,
                                             weights().node_offsets(cell, k)) :
                    Tensor<2, dim>(),
                  cell.size,
                  chunk_findings[chunk]);
              }
          });
      }
    else
      {
        // grad v_p summed over the point's entries (one thread: a point's
        // entries lie in several cells).
        const unsigned int n_points = this->points.size();
        point_gradients.assign(n_points, Tensor<2, dim>());
        for (const auto &cell : this->active_cells)
          {
            const VertexValues v_node = this->read_nodes(cell, velocity);
            const unsigned int end    = cell.first_entry + cell.n_points;
            for (unsigned int k = cell.first_entry; k < end; ++k)
              point_gradients[weights().point_of_entry(k)] +=
                entry_gradient(k, v_node);
          }
        // A point that takes the gradient as C_p needs its second moment:
        // map_mass_and_momentum() of this step summed them over the same
        // entries into point_second_moment (APIC on these weights always
        // does; the entries do not change within a step).
        Assert(!set_affine || (this->get_transfer().apic() != nullptr &&
                               point_second_moment.size() == n_points),
               ExcInternalError());
        if (patch)
          patch_mean_rates_over_point_cells(volume_weighted_trace);
        // The points in chunks of their own cells (point_cell_begin).
        for_point_cells([&](const unsigned int c, const unsigned int chunk) {
          const unsigned int begin = point_cell_begin[c];
          const unsigned int end   = point_cell_begin[c + 1];
          if (patch)
            PointUpdate<dim>::set_volumetric_part(
              point_gradients.data() + begin, end - begin, cell_patch_means[c]);
          else if (average)
            PointUpdate<dim>::average_volumetric_part(
              this->points.data() + begin,
              point_gradients.data() + begin,
              end - begin);
          for (unsigned int p = begin; p < end; ++p)
            update_point(p,
                         point_gradients[p],
                         store_gradient(this->points[p]) ?
                           point_second_moment[p] :
                           Tensor<2, dim>(),
                         point_cell_size[c],
                         chunk_findings[chunk]);
        });
      }
    record_chunk_findings();
  }


  template <int dim, class Weights>
  void
  ParticleGridPasses<dim, Weights>::round_trip(const NodalVector &velocity,
                                               NodalVector       &momentum)
  {
    using Layout = PropertyLayout<dim>;
    // The velocity interpolated at entry k of a cell with nodal values
    // @p u_node.
    const auto interpolate = [this](const unsigned int  k,
                                    const VertexValues &u_node) {
      const auto    &N = this->shape_functions[k].value;
      Tensor<1, dim> v;
      for (unsigned int i = 0; i < n_vertices; ++i)
        v += N[i] * u_node[i];
      return v;
    };
    // Entry k's share of its point's momentum m_p v_p back to the nodes.
    const auto project = [this](const unsigned int    k,
                                const Tensor<1, dim> &v_p,
                                VertexValues         &sums) {
      const double m = this->points[weights().point_of_entry(k)][Layout::mass];
      const Tensor<1, dim> mv = m * v_p;
      const auto          &N  = this->shape_functions[k].value;
      for (unsigned int i = 0; i < n_vertices; ++i)
        sums[i] += N[i] * mv;
    };
    if constexpr (!Weights::entries_are_points)
      {
        // S+: each point's velocity, summed over its entries (one thread).
        point_sum_v.assign(this->points.size(), Tensor<1, dim>());
        for (const auto &cell : this->active_cells)
          {
            const VertexValues u_node = this->read_nodes(cell, velocity);
            const unsigned int end    = cell.first_entry + cell.n_points;
            for (unsigned int k = cell.first_entry; k < end; ++k)
              point_sum_v[weights().point_of_entry(k)] +=
                interpolate(k, u_node);
          }
      }
    // S: the points' momentum back to the nodes with the same weights.
    this->zero_touched_entries(momentum);
    this->template for_active_cells<1>(
      {{&momentum}},
      [&](const unsigned int c,
          const unsigned int,
          std::array<VertexValues, 1> &sums) {
        const ActiveCell  &cell = this->active_cells[c];
        const unsigned int end  = cell.first_entry + cell.n_points;
        if constexpr (Weights::entries_are_points)
          {
            const VertexValues u_node = this->read_nodes(cell, velocity);
            for (unsigned int k = cell.first_entry; k < end; ++k)
              project(k, interpolate(k, u_node), sums[0]);
          }
        else
          for (unsigned int k = cell.first_entry; k < end; ++k)
            project(k, point_sum_v[weights().point_of_entry(k)], sums[0]);
      });
    this->add_contributions_of_all_ranks(momentum);
  }


  template <int dim, class Weights>
  void
  ParticleGridPasses<dim, Weights>::second_moments(
    std::vector<Tensor<2, dim>> &D) const
  {
    // D_p = sum_k alpha_k sum_i N_i(x_k) dx_i dx_i^T about the affine
    // centre.
    D.assign(this->points.size(), Tensor<2, dim>());
    unsigned int k = 0;
    for (const auto &cell : this->active_cells)
      for (unsigned int q = 0; q < cell.n_points; ++q, ++k)
        {
          const Tensor<2, dim> D_k =
            Apic<dim>::second_moment(this->shape_functions[k].value,
                                     weights().node_offsets(cell, k));
          if constexpr (Weights::entries_are_points)
            D[k] = D_k;
          else
            D[weights().point_of_entry(k)] += D_k;
        }
  }

  template <int dim, class Weights>
  void
  ParticleGridPasses<dim, Weights>::map_phase(PhaseKernel<dim> &kernel)
  {
    using Kernel                 = PhaseKernel<dim>;
    const typename Kernel::Targets targets = kernel.grid_targets();
    const bool                     affine  = kernel.needs_affine();
    this->template for_active_cells<Kernel::max_targets>(
      targets,
      [&](const unsigned int c,
          const unsigned int,
          typename Kernel::Sums &sums) {
        const ActiveCell  &cell = this->active_cells[c];
        const unsigned int end  = cell.first_entry + cell.n_points;
        VertexValues       offsets{};
        for (unsigned int k = cell.first_entry; k < end; ++k)
          {
            if (affine)
              offsets = weights().node_offsets(cell, k);
            kernel.add_to_grid(this->points[weights().point_of_entry(k)],
                               this->shape_functions[k],
                               offsets,
                               sums);
          }
      });
    for (NodalVector *target : targets)
      if (target != nullptr)
        this->add_contributions_of_all_ranks(*target);
  }


  template <int dim, class Weights>
  void
  ParticleGridPasses<dim, Weights>::update_phase_points(
    PhaseKernel<dim> &kernel)
  {
    using Kernel                      = PhaseKernel<dim>;
    constexpr unsigned int n_sources  = Kernel::max_sources;
    const typename Kernel::Sources sources = kernel.grid_sources();
    // The kernel's affine fit of its first source: APIC's B D^-1 where the
    // weights' second moment is bounded below (CPDI) and the point's fit is
    // stable there (Weights::fit_is_stable(): not a domain scaled down to
    // nearly the linear weights), else (linear weights, whose D vanishes
    // on cell edges) the gradient, as the skeleton's APIC under MUSL.
    const bool affine = kernel.needs_affine() && sources[0] != nullptr;
    const bool fit_by_moments =
      affine && weights().second_moment_bounded_below();
    // One entry's values and gradients of every source, added to @p value
    // and @p gradient, and to the affine fit's sums @p fit (or nullptr).
    const auto add_entry = [&](const ActiveCell  &cell,
                               const unsigned int k,
                               Tensor<1, dim>    *value,
                               Tensor<2, dim>    *gradient,
                               AffineFitSums     *fit) {
      const auto &sf = this->shape_functions[k];
      for (unsigned int s = 0; s < n_sources; ++s)
        if (sources[s] != nullptr)
          {
            const VertexValues u = this->read_nodes(cell, *sources[s]);
            for (unsigned int i = 0; i < n_vertices; ++i)
              {
                value[s] += sf.value[i] * u[i];
                gradient[s] += outer_product(u[i], sf.gradient[i]);
              }
            if (s == 0 && fit != nullptr)
              add_to_affine_fit(cell, k, u, *fit);
          }
    };
    const auto affine_fit = [&](const double         *props,
                                const AffineFitSums  &fit,
                                const Tensor<2, dim> &gradient) {
      if (!affine)
        return Tensor<2, dim>();
      if (!fit_by_moments || !weights().fit_is_stable(props))
        return gradient;
      return Apic<dim>::affine_fit(fit.B, fit.D, fit.gradient, fit.node_scale);
    };
    const bool cell_means = kernel.averages_over_cells();
    const bool patches    = cell_means && kernel.averages_over_patches();
    // Point p's rate for the kernel's means and its weight.
    const auto kernel_rate = [&](const unsigned int    p,
                                 const PhasePointSums &sums) {
      return kernel.cell_rate(this->points[p], sums.values, sums.gradients);
    };
    if constexpr (Weights::entries_are_points)
      {
        if (cell_means)
          chunk_phase_scratch.resize(
            chunk_count(this->active_cells.size(), this->cell_chunk_size));
        if (patches)
          {
            // Every point's sums first, then the patches' means of their
            // rates, then the points cell by cell.
            phase_point_sums.resize(this->points.size());
            for_each_chunk(
              this->active_cells.size(),
              this->cell_chunk_size,
              [&](const unsigned int,
                  const unsigned int first,
                  const unsigned int last) {
                for (unsigned int c = first; c < last; ++c)
                  {
                    const ActiveCell  &cell = this->active_cells[c];
                    const unsigned int end  = cell.first_entry + cell.n_points;
                    for (unsigned int k = cell.first_entry; k < end; ++k)
                      {
                        PhasePointSums &sums = phase_point_sums[k];
                        sums                 = PhasePointSums();
                        AffineFitSums fit;
                        add_entry(cell,
                                  k,
                                  sums.values.data(),
                                  sums.gradients.data(),
                                  fit_by_moments ? &fit : nullptr);
                        sums.affine =
                          affine_fit(this->points[k], fit, sums.gradients[0]);
                      }
                  }
              });
            patch_mean_rates_over_point_cells([&](const unsigned int p) {
              return kernel_rate(p, phase_point_sums[p]);
            });
            for_each_chunk(
              this->active_cells.size(),
              this->cell_chunk_size,
              [&](const unsigned int chunk,
                  const unsigned int first,
                  const unsigned int last) {
                PhaseCellScratch &scratch = chunk_phase_scratch[chunk];
                for (unsigned int c = first; c < last; ++c)
                  {
                    const ActiveCell &cell = this->active_cells[c];
                    scratch.sums.assign(phase_point_sums.begin() +
                                          cell.first_entry,
                                        phase_point_sums.begin() +
                                          cell.first_entry + cell.n_points);
                    update_phase_points_of_cell(kernel,
                                                cell.first_entry,
                                                cell.first_point,
                                                scratch,
                                                &cell_patch_means[c]);
                  }
              });
            return;
          }
        for_each_chunk(
          this->active_cells.size(),
          this->cell_chunk_size,
          [&](const unsigned int chunk,
              const unsigned int first,
              const unsigned int last) {
            for (unsigned int c = first; c < last; ++c)
              {
                const ActiveCell  &cell = this->active_cells[c];
                const unsigned int end  = cell.first_entry + cell.n_points;
                if (cell_means)
                  {
                    PhaseCellScratch &scratch = chunk_phase_scratch[chunk];
                    scratch.sums.assign(cell.n_points, {});
                    for (unsigned int k = cell.first_entry; k < end; ++k)
                      {
                        PhasePointSums &sums =
                          scratch.sums[k - cell.first_entry];
                        AffineFitSums fit;
                        add_entry(cell,
                                  k,
                                  sums.values.data(),
                                  sums.gradients.data(),
                                  fit_by_moments ? &fit : nullptr);
                        sums.affine =
                          affine_fit(this->points[k], fit, sums.gradients[0]);
                      }
                    update_phase_points_of_cell(kernel,
                                                cell.first_entry,
                                                cell.first_point,
                                                scratch);
                    continue;
                  }
                for (unsigned int k = cell.first_entry; k < end; ++k)
                  {
                    std::array<Tensor<1, dim>, n_sources> values;
                    std::array<Tensor<2, dim>, n_sources> gradients;
                    AffineFitSums                       fit;
                    add_entry(cell,
                              k,
                              values.data(),
                              gradients.data(),
                              fit_by_moments ? &fit : nullptr);
                    kernel.update_point(this->points[k],
                                        values,
                                        gradients,
                                        affine_fit(this->points[k],
                                                   fit,
                                                   gradients[0]));
                  }
              }
          });
      }
    else
      {
        // A point's entries lie in several cells: summed per point first
        // (on one thread, in the order of the entries), then each point
        // updated.
        const unsigned int n_points = this->points.size();
        phase_values.assign(std::size_t(n_points) * n_sources,
                            Tensor<1, dim>());
        phase_gradients.assign(std::size_t(n_points) * n_sources,
                               Tensor<2, dim>());
        phase_affine_sums.assign(fit_by_moments ? n_points : 0,
                                 AffineFitSums());
        for (const ActiveCell &cell : this->active_cells)
          {
            const unsigned int end = cell.first_entry + cell.n_points;
            for (unsigned int k = cell.first_entry; k < end; ++k)
              {
                const std::size_t p = weights().point_of_entry(k);
                add_entry(cell,
                          k,
                          &phase_values[p * n_sources],
                          &phase_gradients[p * n_sources],
                          fit_by_moments ? &phase_affine_sums[p] : nullptr);
              }
          }
        const auto affine_of_point = [&](const unsigned int p) {
          return affine_fit(this->points[p],
                            fit_by_moments ? phase_affine_sums[p] :
                                             AffineFitSums(),
                            phase_gradients[std::size_t(p) * n_sources]);
        };
        if (cell_means)
          {
            const unsigned int n_point_cells =
              point_cell_begin.empty() ? 0 : point_cell_begin.size() - 1;
            if (patches)
              patch_mean_rates_over_point_cells([&](const unsigned int p) {
                PhasePointSums sums;
                for (unsigned int s = 0; s < n_sources; ++s)
                  {
                    sums.values[s] =
                      phase_values[std::size_t(p) * n_sources + s];
                    sums.gradients[s] =
                      phase_gradients[std::size_t(p) * n_sources + s];
                  }
                return kernel_rate(p, sums);
              });
            // The points in chunks of their own cells (point_cell_begin).
            chunk_phase_scratch.resize(
              chunk_count(n_point_cells, this->cell_chunk_size));
            for_point_cells([&](const unsigned int c,
                                const unsigned int chunk) {
              PhaseCellScratch &scratch = chunk_phase_scratch[chunk];
              scratch.sums.resize(point_cell_begin[c + 1] -
                                  point_cell_begin[c]);
              for (unsigned int p = point_cell_begin[c];
                   p < point_cell_begin[c + 1];
                   ++p)
                {
                  PhasePointSums &sums = scratch.sums[p - point_cell_begin[c]];
                  for (unsigned int s = 0; s < n_sources; ++s)
                    {
                      sums.values[s] =
                        phase_values[std::size_t(p) * n_sources + s];
                      sums.gradients[s] =
                        phase_gradients[std::size_t(p) * n_sources + s];
                    }
                  sums.affine = affine_of_point(p);
                }
              update_phase_points_of_cell(kernel,
                                          point_cell_begin[c],
                                          point_cell_first_point[c],
                                          scratch,
                                          patches ? &cell_patch_means[c] :
                                                    nullptr);
            });
            return;
          }
        for_each_chunk(n_points,
                       chunk_size_for(n_points),
                       [&](const unsigned int,
                           const unsigned int first,
                           const unsigned int last) {
                         for (unsigned int p = first; p < last; ++p)
                           {
                             std::array<Tensor<1, dim>, n_sources> values;
                             std::array<Tensor<2, dim>, n_sources> gradients;
                             for (unsigned int s = 0; s < n_sources; ++s)
                               {
                                 values[s] =
                                   phase_values[std::size_t(p) * n_sources + s];
                                 gradients[s] =
                                   phase_gradients[std::size_t(p) * n_sources +
                                                   s];
                               }
                             kernel.update_point(this->points[p],
                                                 values,
                                                 gradients,
                                                 affine_of_point(p));
                           }
                       });
      }
  }


  template <int dim, class Weights>
  void
  ParticleGridPasses<dim, Weights>::update_phase_points_of_cell(
    const PhaseKernel<dim>                                     &kernel,
    const unsigned int                                          first,
    typename Particles::ParticleHandler<dim>::particle_iterator first_point,
    PhaseCellScratch                                           &scratch,
    const double *patch_mean) const
  {
    const unsigned int n = scratch.sums.size();
    if (n == 0)
      return;
    double mean = 0;
    if (patch_mean != nullptr)
      mean = *patch_mean;
    else
      {
        double sum = 0, weight = 0;
        for (unsigned int q = 0; q < n; ++q)
          {
            const PhasePointSums &sums = scratch.sums[q];
            const auto [rate, w] = kernel.cell_rate(this->points[first + q],
                                                    sums.values,
                                                    sums.gradients);
            sum += w * rate;
            weight += w;
          }
        mean = weight > 0 ? sum / weight : 0.;
      }
    scratch.positions.clear();
    auto point = first_point;
    for (unsigned int q = 0; q < n; ++q, ++point)
      {
        const PhasePointSums &sums = scratch.sums[q];
        kernel.update_point_with_cell_mean(this->points[first + q],
                                           sums.values,
                                           sums.gradients,
                                           sums.affine,
                                           mean);
        scratch.positions.push_back(point->get_location());
      }
    kernel.finish_cell(ArrayView<double *const>(&this->points[first], n),
                       make_array_view(scratch.positions),
                       first_point->get_surrounding_cell()->measure());
  }
} // namespace MPM

#endif

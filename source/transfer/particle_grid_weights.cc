#include <mpm/parallel/thread_chunks.h>
#include <mpm/transfer/particle_grid_weights.h>
#include <mpm/transfer/point_domains.h>

#include <algorithm>
#include <limits>

namespace MPM
{
  template <int dim>
  ParticleGridWeights<dim>::ParticleGridWeights(Simulator<dim> &simulator)
      : SimulatorAccess<dim>(simulator)
  {}


  template <int dim>
  void
  ParticleGridWeights<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Transfer");
    prm.declare_entry(
      "Particle-grid weights",
      "cpdi",
      Patterns::Selection(ParticleGridWeightsRegistry<dim>::names()),
      "The weights by which points and nodes exchange mass, momentum and "
      "force. 'cpdi' (the default): the point's parallelogram domain, "
      "which deforms with it, averages the mesh functions over it "
      "(Sadeghirad et al. 2011); smooth across cell edges, the weights "
      "on which APIC converges (doc/convergence.md). 'linear': the "
      "mesh's bilinear functions at the point (a point acts on the "
      "vertices of its cell only: forces jump when it crosses a cell "
      "edge, the cell-crossing noise that grows under refinement); "
      "cheaper (doc/performance.md has the ratio).");
    prm.leave_subsection();
    PointDomains<dim>::declare_parameters(prm);
  }


  template <int dim>
  std::unique_ptr<ParticleGridWeights<dim>>
  ParticleGridWeights<dim>::create(ParameterHandler &prm,
                                   Simulator<dim>   &simulator)
  {
    prm.enter_subsection("Transfer");
    const std::string name = prm.get("Particle-grid weights");
    prm.leave_subsection();
    return ParticleGridWeightsRegistry<dim>::create(
      name, "Transfer/Particle-grid weights", prm, simulator);
  }


  template <int dim>
  void
  ParticleGridWeights<dim>::setup_partition()
  {
    const NodalVector &v = this->get_nodal_fields().mass;
    chunk_of_dof.assign(v.locally_owned_size() +
                          v.get_partitioner()->n_ghost_indices(),
                        untouched);
    touched_dofs.clear();
  }


  template <int dim>
  void
  ParticleGridWeights<dim>::zero_touched_entries(NodalVector &v) const
  {
    // Only the entries the previous step touched are non-zero: those of
    // this rank's points (owned or ghost) and the owned entries other
    // ranks added to in compress() (the partitioner's import indices).
    for (const unsigned int i : touched_dofs)
      v.local_element(i) = 0;
    for (const auto &range : v.get_partitioner()->import_indices())
      for (unsigned int i = range.first; i < range.second; ++i)
        v.local_element(i) = 0;
    v.zero_out_ghost_values();
  }


  template <int dim>
  void
  ParticleGridWeights<dim>::clear_active_cells()
  {
    active_cells.clear();
    touched_dofs.clear();
    shortest_edge = std::numeric_limits<double>::max();
  }


  template <int dim>
  void
  ParticleGridWeights<dim>::add_active_cell(
    const unsigned int cell_index,
    const unsigned int n,
    const typename Particles::ParticleHandler<dim>::particle_iterator
      &first_point)
  {
    const BackgroundGrid<dim> &grid = this->get_grid();
    ActiveCell active{};
    active.n_points    = n;
    active.dofs        = this->get_cell_dofs()[cell_index];
    active.vertices    = &grid.cell_vertices(cell_index);
    active.size        = grid.cell_size(cell_index);
    active.first_entry = active_cells.empty() ?
                           0 :
                           active_cells.back().first_entry +
                             active_cells.back().n_points;
    active.first_point = first_point;
    shortest_edge = std::min(shortest_edge, active.size);
    if constexpr (dim == 2)
      active.map = &grid.bilinear_map(cell_index);
    else if (grid.parallelepiped_map(cell_index).is_affine())
      active.parallelepiped = &grid.parallelepiped_map(cell_index);
    active_cells.push_back(active);
  }


  template <int dim>
  double
  ParticleGridWeights<dim>::finish_active_cells()
  {
    const unsigned int n_cells = active_cells.size();
    cell_chunk_size            = chunk_size_for(n_cells);
    // The nodal entries of the cells, in the order they are first touched,
    // and (by the first component's entry: a vertex's components are
    // touched by the same cells) the chunk of the cells that touch each,
    // or shared_by_chunks.
    for (unsigned int c = 0; c < n_cells; ++c)
      {
        const unsigned int this_chunk = c / cell_chunk_size;
        for (const auto &vertex_dofs : active_cells[c].dofs)
          {
            if (chunk_of_dof[vertex_dofs[0]] == untouched)
              {
                for (const unsigned int local : vertex_dofs)
                  touched_dofs.push_back(local);
                chunk_of_dof[vertex_dofs[0]] = this_chunk;
              }
            else if (chunk_of_dof[vertex_dofs[0]] != this_chunk)
              chunk_of_dof[vertex_dofs[0]] = shared_by_chunks;
          }
      }
    // The cells with vertices that cells of other chunks share (none with
    // one chunk).
    cells_on_chunk_borders.clear();
    if (n_cells > cell_chunk_size)
      for (unsigned int c = 0; c < n_cells; ++c)
        {
          ActiveCell &cell = active_cells[c];
          for (unsigned int i = 0; i < n_vertices; ++i)
            if (chunk_of_dof[cell.dofs[i][0]] == shared_by_chunks)
              cell.vertices_shared_with_other_chunks |= (1u << i);
          if (cell.vertices_shared_with_other_chunks != 0)
            {
              cell.border_index = cells_on_chunk_borders.size();
              cells_on_chunk_borders.push_back(c);
            }
        }
    // The copies of a touched periodic node are touched too: the
    // particle-to-grid sums give them values (PeriodicNodeGroups), so
    // they are updated and zeroed with the rest.
    if (!this->get_periodic_nodes().empty())
      {
        is_touched.resize(chunk_of_dof.size(), false);
        for (const unsigned int i : touched_dofs)
          is_touched[i] = true;
        const unsigned int n_touched_by_cells = touched_dofs.size();
        for (unsigned int k = 0; k < n_touched_by_cells; ++k)
          this->get_periodic_nodes().for_each_copy(touched_dofs[k],
                                                   [&](const unsigned int j) {
                                                     if (!is_touched[j])
                                                       {
                                                         is_touched[j] = true;
                                                         touched_dofs.push_back(
                                                           j);
                                                       }
                                                   });
        for (const unsigned int i : touched_dofs)
          is_touched[i] = false;
      }
    for (const unsigned int i : touched_dofs)
      chunk_of_dof[i] = untouched;
    return shortest_edge;
  }


  template class ParticleGridWeights<2>;
  template class ParticleGridWeights<3>;
} // namespace MPM

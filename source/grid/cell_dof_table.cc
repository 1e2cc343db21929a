#include <deal.II/dofs/dof_handler.h>

#include <mpm/grid/cell_dof_table.h>

namespace MPM
{
  template <int dim>
  void
  CellDofTable<dim>::reinit(const BackgroundGrid<dim>          &grid,
                            const Utilities::MPI::Partitioner &partitioner)
  {
    using DoFCellIterator = typename DoFHandler<dim>::active_cell_iterator;
    std::vector<types::global_dof_index> cell_dofs(grid.fe.n_dofs_per_cell());
    table.assign(grid.triangulation.n_active_cells(), {});
    for (const auto &tria_cell : grid.triangulation.active_cell_iterators())
      if (!tria_cell->is_artificial())
        {
          const DoFCellIterator cell(&grid.triangulation,
                                     tria_cell->level(),
                                     tria_cell->index(),
                                     &grid.dof_handler);
          cell->get_dof_indices(cell_dofs);
          auto &local = table[tria_cell->active_cell_index()];
          for (const unsigned int v : cell->vertex_indices())
            {
              for (unsigned int c = 0; c < dim; ++c)
                local[v][c] = partitioner.global_to_local(
                  cell_dofs[grid.fe.component_to_system_index(c, v)]);
              // deal.II numbers a vertex's dim components consecutively,
              // a rank owns all of a vertex's, and the partitioner keeps
              // owned and ghost entries in global order: a node's
              // components are the local entries dim k ... dim k + dim - 1,
              // which per-node loops over the entries rely on
              // (SideWallFriction::apply()).
              for (unsigned int c = 0; c < dim; ++c)
                AssertThrow(local[v][c] == local[v][0] + c &&
                              local[v][0] % dim == 0,
                            ExcMessage("A node's components are not the "
                                       "nodal-vector entries dim k + c."));
            }
        }
  }


  template class CellDofTable<2>;
  template class CellDofTable<3>;
} // namespace MPM

#ifndef mpm_grid_cell_dof_table_h
#define mpm_grid_cell_dof_table_h

#include <deal.II/base/geometry_info.h>
#include <deal.II/base/partitioner.h>

#include <mpm/grid/background_grid.h>

#include <array>
#include <vector>

namespace MPM
{
  using namespace dealii;

  /**
   * The nodal-vector entries of each cell's vertex degrees of freedom: the
   * local indices (owned and ghost) of its dim components per vertex, by
   * active_cell_index(), for every non-artificial cell (ghost cells too:
   * CPDI's domains reach into them). Looked up once per partition from the
   * DoFHandler and the partitioner (reinit()), so that the particle-grid
   * passes touch neither in a step.
   */
  template <int dim>
  class CellDofTable
  {
  public:
    /// A cell's entries, as [vertex][component].
    using VertexDofs =
      std::array<std::array<unsigned int, dim>,
                 GeometryInfo<dim>::vertices_per_cell>;

    /// The table of @p grid's cells in the numbering of @p partitioner
    /// (the nodal vectors' layout).
    void
    reinit(const BackgroundGrid<dim>          &grid,
           const Utilities::MPI::Partitioner &partitioner);

    const VertexDofs &
    operator[](const unsigned int active_cell_index) const
    {
      return table[active_cell_index];
    }

  private:
    std::vector<VertexDofs> table;
  };
} // namespace MPM

#endif

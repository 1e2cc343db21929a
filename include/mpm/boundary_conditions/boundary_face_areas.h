#ifndef mpm_boundary_conditions_boundary_face_areas_h
#define mpm_boundary_conditions_boundary_face_areas_h

#include <deal.II/base/quadrature_lib.h>

#include <deal.II/fe/fe_values.h>

#include <mpm/grid/background_grid.h>

namespace MPM
{
  using namespace dealii;

  /**
   * Every boundary face of the locally owned cells whose boundary id
   * @p on_face accepts, with the mesh's own map and a 2-point Gauss rule
   * per face direction: @p visit(cell, face_no, id, face_values), the
   * FEFaceValues reinitialised on the face with @p flags. Sums over ranks
   * are the caller's.
   */
  template <int dim, typename Accept, typename Visit>
  void
  for_each_boundary_face(const BackgroundGrid<dim> &grid,
                         const Accept              &on_face,
                         const UpdateFlags          flags,
                         const Visit               &visit)
  {
    FEFaceValues<dim> face_values(grid.mapping,
                                  grid.fe,
                                  QGauss<dim - 1>(2),
                                  flags);
    for (const auto &cell : grid.dof_handler.active_cell_iterators())
      {
        if (!cell->is_locally_owned())
          continue;
        for (const unsigned int f : cell->face_indices())
          {
            if (!cell->face(f)->at_boundary())
              continue;
            const types::boundary_id id = cell->face(f)->boundary_id();
            if (!on_face(id))
              continue;
            face_values.reinit(cell, f);
            visit(cell, f, id, face_values);
          }
      }
  }


  /// The shape function of the cell's vertex @p cell_vertex in @p grid's
  /// finite element (its component 0).
  template <int dim>
  unsigned int
  vertex_shape_function(const BackgroundGrid<dim> &grid,
                        const unsigned int         cell_vertex)
  {
    return grid.fe.component_to_system_index(0, cell_vertex);
  }


  /**
   * The nodes' shares of boundary faces, A_v = int_face N_v dA
   * (for_each_boundary_face()): for each face @p on_face accepts, call
   * @p add(cell, cell_vertex, id, A_v) for the face's vertices (numbered
   * as the cell's, so cell->vertex_dof_index() finds their entries). What
   * a traction on a boundary does at the nodes (SurfaceTractions, a
   * wall's area for friction in effective stress). Sums over ranks are
   * the caller's.
   */
  template <int dim, typename Accept, typename Add>
  void
  for_each_boundary_face_node_area(const BackgroundGrid<dim> &grid,
                                   const Accept              &on_face,
                                   const Add                 &add)
  {
    for_each_boundary_face(
      grid,
      on_face,
      update_values | update_JxW_values,
      [&](const auto               &cell,
          const unsigned int        f,
          const types::boundary_id  id,
          const FEFaceValues<dim>  &face_values) {
        for (unsigned int v = 0; v < cell->face(f)->n_vertices(); ++v)
          {
            const unsigned int cell_vertex =
              GeometryInfo<dim>::face_to_cell_vertices(f, v);
            const unsigned int i = vertex_shape_function(grid, cell_vertex);
            double             area = 0;
            for (unsigned int q = 0; q < face_values.n_quadrature_points; ++q)
              area += face_values.shape_value(i, q) * face_values.JxW(q);
            add(cell, cell_vertex, id, area);
          }
      });
  }
} // namespace MPM

#endif

#ifndef mpm_boundary_conditions_boundary_face_areas_h
#define mpm_boundary_conditions_boundary_face_areas_h

#include <deal.II/base/quadrature_lib.h>

#include <deal.II/fe/fe_values.h>

#include <mpm/grid/background_grid.h>

namespace MPM
{
  using namespace dealii;

  /**
   * The nodes' shares of boundary faces, A_v = int_face N_v dA (2-point
   * Gauss rule per face direction, the mesh's own map): for every locally
   * owned cell and each of its boundary faces whose boundary id
   * @p on_face accepts, call @p add(cell, cell_vertex, id, A_v) for the
   * face's vertices (numbered as the cell's, so cell->vertex_dof_index()
   * finds their entries). What a pressure or a traction on a boundary
   * does at the nodes (SurfaceTractions, a wall's area for friction in
   * effective stress). Sums over ranks are the caller's.
   */
  template <int dim, typename Accept, typename Add>
  void
  for_each_boundary_face_node_area(const BackgroundGrid<dim> &grid,
                                   const Accept              &on_face,
                                   const Add                 &add)
  {
    FEFaceValues<dim> face_values(grid.mapping,
                                  grid.fe,
                                  QGauss<dim - 1>(2),
                                  update_values | update_JxW_values);
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
            for (unsigned int v = 0; v < cell->face(f)->n_vertices(); ++v)
              {
                const unsigned int cell_vertex =
                  GeometryInfo<dim>::face_to_cell_vertices(f, v);
                // The shape function of the vertex (component 0).
                const unsigned int i =
                  grid.fe.component_to_system_index(0, cell_vertex);
                double area = 0;
                for (unsigned int q = 0; q < face_values.n_quadrature_points;
                     ++q)
                  area += face_values.shape_value(i, q) * face_values.JxW(q);
                add(cell, cell_vertex, id, area);
              }
          }
      }
  }
} // namespace MPM

#endif

#ifndef mpm_boundary_conditions_boundary_pore_pressures_h
#define mpm_boundary_conditions_boundary_pore_pressures_h

#include <deal.II/base/function_parser.h>

#include <mpm/boundary_conditions/boundary_spec.h>
#include <mpm/grid/background_grid.h>
#include <mpm/grid/nodal_vector.h>
#include <mpm/grid/periodic_node_groups.h>

#include <array>
#include <memory>
#include <vector>

namespace MPM
{
  using namespace dealii;

  /**
   * The boundaries with a prescribed 'Pore pressure' p_b: water at that
   * pressure stands on their faces and passes through them (a reservoir
   * over a submerged slope, an artesian layer below a drained base). On
   * the mixture it is the load -p_b n dA (n the outward normal): nodal
   * forces F_i = -int_face N_i p_b n dA, of which the pore water takes the
   * nodal porosity's share and the skeleton the rest (PoreWater::
   * couple()): the water's share is the boundary term of its momentum
   * balance that a boundary without a pressure leaves out (p_b = 0 there,
   * doc/pore_water.md).
   *
   * p_b is a function of the scene's coordinates and the time, evaluated
   * at the faces' quadrature points (two per face direction): a pressure
   * linear along a face, as the hydrostatic one, is integrated exactly.
   * The forces are assembled at setup() and again each step only if a
   * boundary's expression names t.
   */
  template <int dim>
  class BoundaryPorePressures
  {
  public:
    /**
     * The quadrature data of the faces of the boundaries of @p specs with
     * a pore pressure, on the mesh and DoF numbering of @p grid, and their
     * forces at time 0 in the layout of the ghosted vector @p layout
     * (summed over ranks and periodic copies). Throws an InputError
     * naming the boundary if an expression cannot be evaluated.
     */
    void
    setup(const BackgroundGrid<dim>            &grid,
          const std::vector<BoundarySpec<dim>> &specs,
          const NodalVector                    &layout,
          const PeriodicNodeGroups             *periodic_nodes);

    /// Whether any boundary has a pore pressure.
    bool
    any() const
    {
      return !functions.empty();
    }

    /**
     * The nodal forces F_i of the pressures at time @p time (all
     * components, the mesh frame), or nullptr if no boundary has a pore
     * pressure.
     */
    const NodalVector *
    forces_at(const double time);

  private:
    static constexpr unsigned int vertices_per_face =
      GeometryInfo<dim>::vertices_per_face;

    /// One face quadrature point: where p_b is evaluated, and what it
    /// gives the face's vertices.
    struct FacePoint
    {
      /// Index into functions.
      unsigned int boundary;
      /// The quadrature point in the scene's frame.
      Point<dim> x;
      /// Each vertex's DoF of each component.
      std::array<std::array<types::global_dof_index, dim>, vertices_per_face>
        dofs;
      /// Each vertex's N_v JxW n at the point (mesh frame).
      std::array<Tensor<1, dim>, vertices_per_face> weight;
    };

    void
    assemble(const double time);

    std::vector<std::unique_ptr<FunctionParser<dim>>> functions;
    std::vector<FacePoint>                            face_points;
    bool                      time_dependent = false;
    double                    assembled_time = 0;
    const PeriodicNodeGroups *periodic       = nullptr;
    NodalVector               nodal_force;
  };
} // namespace MPM

#endif

#ifndef mpm_transfer_linear_weights_h
#define mpm_transfer_linear_weights_h

#include <mpm/transfer/particle_grid_passes.h>

namespace MPM
{
  using namespace dealii;

  /**
   * 'Particle-grid weights = linear': the mesh's own bilinear (trilinear)
   * functions at each point, evaluated from the point's reference
   * coordinates in its cell (the inverse isoparametric map). A point acts
   * on the vertices of its cell only, so its force on a node jumps when it
   * crosses a cell edge (the cell-crossing error; CpdiWeights has none).
   * The cheapest weights: each pass visits the points cell by cell, reads
   * a cell's nodal values once for all its points and adds their sums to
   * the nodes once.
   */
  template <int dim>
  class LinearWeights : public ParticleGridPasses<dim, LinearWeights<dim>>
  {
  public:
    using typename ParticleGridWeights<dim>::VertexValues;
    using ParticleGridWeights<dim>::n_vertices;

    /// No parameters of its own (@p prm is unused).
    LinearWeights(Simulator<dim> &simulator, ParameterHandler &prm);

  protected:
    double
    prepare() override;

  private:
    friend class ParticleGridPasses<dim, LinearWeights<dim>>;
    using typename ParticleGridWeights<dim>::ActiveCell;

    /// @name The hooks of ParticleGridPasses: one entry per point, at the
    /// point, with the mesh functions' values and gradients there.
    /// @{
    static constexpr bool entries_are_points = true;

    static unsigned int
    point_of_entry(const unsigned int k)
    {
      return k;
    }

    VertexValues
    node_offsets(const ActiveCell &cell, const unsigned int k) const
    {
      return this->vertex_offsets(cell, this->shape_functions[k]);
    }

    static void
    deform_with_point(const unsigned int,
                      double *,
                      const Tensor<2, dim> &,
                      const double)
    {}

    static const BilinearCellMap *
    cell_map_of_point(const unsigned int)
    {
      return nullptr;
    }

    /// No point's second moment is bounded below (it vanishes on cell
    /// edges): under MUSL APIC takes C_p from the remapped velocity.
    static bool
    fit_is_stable(const double *)
    {
      return false;
    }
    /// @}
  };
} // namespace MPM

#endif

#ifndef mpm_transfer_linear_weights_h
#define mpm_transfer_linear_weights_h

#include <mpm/transfer/particle_grid_weights.h>

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
  class LinearWeights : public ParticleGridWeights<dim>
  {
  public:
    using typename ParticleGridWeights<dim>::VertexValues;
    using ParticleGridWeights<dim>::n_vertices;

    /// No parameters of its own (@p prm is unused).
    LinearWeights(const TransferContext<dim> &context, ParameterHandler &prm);

    double
    prepare() override;

    void
    map_mass_and_momentum(const bool with_forces) override;

    void
    map_forces() override;

    double
    update_points_from_grid(const bool remap_momentum) override;

    void
    update_stress(const NodalVector &velocity, const bool set_affine) override;

    void
    round_trip(const NodalVector &velocity, NodalVector &momentum) override;

    void
    second_moments(std::vector<Tensor<2, dim>> &D) const override;

  private:
    using typename ParticleGridWeights<dim>::ActiveCell;

    /**
     * Add one point's forces (gravity and the divergence of its stress,
     * with its shape functions @p sf) to the sums @p forces over the
     * vertices of its cell.
     */
    static void
    add_point_forces(const double                *props,
                     const Q1ShapeFunctions<dim> &sf,
                     const Tensor<1, dim>        &gravity,
                     VertexValues                &forces);

    /// The velocity gradients of a cell's points (stress update).
    std::vector<Tensor<2, dim>> cell_gradients;
  };
} // namespace MPM

#endif

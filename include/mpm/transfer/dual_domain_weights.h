#ifndef mpm_transfer_dual_domain_weights_h
#define mpm_transfer_dual_domain_weights_h

#include <mpm/transfer/linear_weights.h>

namespace MPM
{
  using namespace dealii;

  /**
   * 'Particle-grid weights = dual domain': the mesh's linear functions at
   * each point for mass and momentum (LinearWeights: one entry per point),
   * with the gradients of the dual domain material point method (Zhang,
   * Ma and Giguere 2011, in its node-averaged form): the stress reaches
   * the nodes as a field, sigma_j = sum_p N_jp V_p sigma_p / V_j, whose
   * divergence is integrated over the active cells (weighted by the share
   * of each cell the material fills), and a point's velocity gradient is
   * interpolated from the nodes' averages L_j of the grid velocity's
   * gradient. Both are continuous as a point crosses a cell edge, which
   * the linear weights' gradients are not (the cell-crossing error), at
   * the cost of the linear weights and a pass over the active cells;
   * the power of the stress stays exact (ParticleGridPasses::
   * add_dual_domain_forces()). doc/transfers.md has its measured errors.
   */
  template <int dim>
  class DualDomainWeights : public LinearWeights<dim>
  {
  public:
    DualDomainWeights(Simulator<dim> &simulator, ParameterHandler &prm);
  };
} // namespace MPM

#endif

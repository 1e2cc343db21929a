// The linear weights with the dual domain gradients; the passes are
// ParticleGridPasses' for the linear weights, switched by dual_domain.

#include <mpm/grid/nodal_vector.h>
#include <mpm/transfer/dual_domain_weights.h>

namespace MPM
{
  template <int dim>
  DualDomainWeights<dim>::DualDomainWeights(Simulator<dim>   &simulator,
                                            ParameterHandler &prm)
      : LinearWeights<dim>(simulator, prm)
  {
    this->dual_domain = true;
    for (NodalVector *field : this->dual_domain_fields())
      this->get_nodal_fields().add(*field, NodalFields::Ghosts::summed);
  }


  template class DualDomainWeights<2>;
  template class DualDomainWeights<3>;
} // namespace MPM

MPM_REGISTER_PARTICLE_GRID_WEIGHTS(
  MPM::DualDomainWeights,
  "dual domain",
  "the mesh's linear functions at the point for mass and momentum; the "
  "forces and the velocity gradient through nodal averages of the stress "
  "and of the velocity gradient (the dual domain material point method), "
  "continuous as points cross cell edges.")

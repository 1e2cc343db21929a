// Modified Update Stress Last (Sulsky et al. 1995): the updated points'
// momenta mapped to the grid again and the stress from that velocity.

#include <deal.II/base/parameter_handler.h>

#include <mpm/solver/step_scheme.h>

namespace MPM
{
  namespace
  {
    class ModifiedUpdateStressLast : public StepScheme
    {
    public:
      explicit ModifiedUpdateStressLast(ParameterHandler &)
      {}

      void
      advance(StepOperations &step) const override
      {
        using V = StepOperations::NodalVelocity;
        step.map_mass_and_momentum(true);
        step.compute_nodal_velocity(V::brought);
        step.filter_brought_velocity();
        step.update_nodal_kinematics();
        // Grid to particle, the new momenta mapped back to the nodes in
        // the same pass.
        step.update_points_from_grid(true);
        step.compute_nodal_velocity(V::updated);
        // APIC takes each point's affine matrix from this velocity's
        // gradient where its fit would be unstable (ParticleGridPasses).
        step.update_stress(V::updated, step.has_affine_transfer());
      }

      bool
      updates_stress_from_remap() const override
      {
        return true;
      }
    };
  } // namespace
} // namespace MPM

MPM_REGISTER_STEP_SCHEME(MPM::ModifiedUpdateStressLast,
                         "MUSL",
                         "Modified Update Stress Last (the default): the "
                         "stress from the velocity remapped from the updated "
                         "points; the scheme of every converged granular "
                         "result in doc/.")

// Update Stress First (Bardenhagen 2002): the stress from the velocity the
// points brought, before the nodal momentum update.

#include <deal.II/base/parameter_handler.h>

#include <mpm/solver/step_scheme.h>

namespace MPM
{
  namespace
  {
    class UpdateStressFirst : public StepScheme
    {
    public:
      explicit UpdateStressFirst(ParameterHandler &)
      {}

      void
      advance(StepOperations &step) const override
      {
        using V = StepOperations::NodalVelocity;
        step.map_mass_and_momentum(false);
        step.compute_nodal_velocity(V::brought);
        step.update_stress(V::brought, false);
        step.map_forces();
        step.filter_brought_velocity();
        step.update_nodal_kinematics();
        step.update_points_from_grid(false);
      }
    };
  } // namespace
} // namespace MPM

MPM_REGISTER_STEP_SCHEME(MPM::UpdateStressFirst,
                         "USF",
                         "Update Stress First: the stress from the velocity "
                         "the points brought, before the nodal momentum "
                         "update, the paper's scheme (on the flume: noise "
                         "at rest, and unstable at the runout in one "
                         "measured configuration; doc/flume.md, \"USF\").")

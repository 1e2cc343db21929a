// Update Stress Last: the stress from the updated nodal velocity, after
// the points have moved.

#include <deal.II/base/parameter_handler.h>

#include <mpm/solver/step_scheme.h>

namespace MPM
{
  namespace
  {
    class UpdateStressLast : public StepScheme
    {
    public:
      explicit UpdateStressLast(ParameterHandler &)
      {}

      void
      advance(StepOperations &step) const override
      {
        using V = StepOperations::NodalVelocity;
        step.map_mass_and_momentum(true);
        step.compute_nodal_velocity(V::brought);
        step.filter_brought_velocity();
        step.update_nodal_kinematics();
        step.update_points_from_grid(false);
        step.update_stress(V::updated, false);
      }
    };
  } // namespace
} // namespace MPM

MPM_REGISTER_STEP_SCHEME(MPM::UpdateStressLast,
                         "USL",
                         "Update Stress Last: the stress from the updated "
                         "nodal velocity, after the points have moved.")

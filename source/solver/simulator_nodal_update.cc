// The Simulator's nodal steps between the particle-grid passes: the
// step's nodal fields zeroed, the nodal velocity the points brought
// (constrained for the strain rate), and the nodal update (forces, basal
// laws, the wall constraints), doc/algorithm.md steps 2 and 6.

#include <mpm/parallel/thread_chunks.h>
#include <mpm/solver/simulator.h>

#include <cmath>

namespace MPM
{
  template <int dim>
  void
  Simulator<dim>::compute_nodal_velocity(NodalVector &velocity_out)
  {
    TimerOutput::Scope t(timer, "nodal update");
    for_each_active_dof([&](const unsigned int i) {
      const double m = nodal.mass.local_element(i);
      velocity_out.local_element(i) =
        m > 0 ? nodal.momentum.local_element(i) / m : 0.;
    });
    // The strain rate's velocity: a node the last nodal update held on its
    // wall stays held (BoundaryConditions::Contact).
    boundary_conditions.project_velocity(
      velocity_out, BoundaryConditions<dim>::Contact::as_last_update);
  }


  template <int dim>
  void
  Simulator<dim>::update_nodal_kinematics()
  {
    TimerOutput::Scope t(timer, "nodal update");
    const double       dt = time_step;
    // Cundall's local damping (with pore water, on the mixture inside
    // PoreWater::couple()).
    const double alpha =
      pore_water.active() ? 0. : time_stepping.local_damping_at(time);
    boundary_conditions.add_traction_forces(nodal.mass,
                                            weights->active_dofs(),
                                            nodal.force);
    if (pore_water.active())
      {
        // The skeleton's force becomes the one that gives its velocity
        // with the water's drag (PoreWater::couple()).
        TimerOutput::Scope t(timer, "pore water");
        weights->map_phase(pore_water);
        pore_water.couple(nodal,
                          weights->active_dofs(),
                          boundary_conditions.pore_pressure_forces(time),
                          time_stepping.local_damping_at(time));
      }
    for_each_active_dof([&](const unsigned int i) {
      const double m = nodal.mass.local_element(i);
      double       f = nodal.force.local_element(i);
      if (alpha > 0)
        {
          // Cundall's local damping: a force against the motion,
          // proportional to the unbalanced force.
          const double v = nodal.velocity.local_element(i);
          f -= alpha * std::abs(f) * (v > 0 ? 1. : v < 0 ? -1. : 0.);
        }
      nodal.acceleration.local_element(i) = m > 0 ? f / m : 0.;
    });
    // The step starts from the velocity the points brought, u = p/m, not
    // from nodal.velocity, in which compute_nodal_velocity() has already
    // removed the normal velocity into the walls (for the stress update).
    // That removal is part of the wall's normal impulse, and Coulomb
    // friction must act on all of it: starting from the constrained
    // velocity left friction out of the impulse with which the wall stops
    // the material arriving at it (in the sliding block, 5e-5 of the
    // normal force, which the friction limit amplified into a 3e-4 error
    // of the acceleration at mu = 0.5). nodal.velocity_new holds u until
    // it is advanced.
    const auto brought_velocity = [this](const unsigned int i) {
      const double m = nodal.mass.local_element(i);
      return m > 0 ? nodal.momentum.local_element(i) / m : 0.;
    };
    for_each_active_dof([&](const unsigned int i) {
      nodal.velocity_new.local_element(i) = brought_velocity(i);
    });
    // The absorbing boundaries' dashpots, implicitly (before the walls:
    // a node of an absorbing face and a wall is damped, then held).
    boundary_conditions.apply_absorbing(
      nodal.mass, nodal.velocity_new, nodal.acceleration, dt, time);
    if (pore_water.active())
      {
        const auto water = pore_water.at_nodes();
        boundary_conditions.apply_friction(
          nodal.mass, nodal.velocity_new, nodal.acceleration, dt, &water);
      }
    else
      boundary_conditions.apply_friction(nodal.mass,
                                         nodal.velocity_new,
                                         nodal.acceleration,
                                         dt);
    for_each_active_dof([&](const unsigned int i) {
      nodal.velocity_new.local_element(i) +=
        dt * nodal.acceleration.local_element(i);
    });
    boundary_conditions.constrain_updated_velocity(nodal.velocity_new);
    if (side_walls.active())
      {
        // On the velocity the mesh's walls have constrained: before it, a
        // node on a wall still has the normal velocity the wall removes,
        // and slowing the whole vector took only part of the friction off
        // its tangential speed (a sliding block's speed ran ahead of its
        // closed form by 4e-4 m/s). Slowing a node along its velocity
        // keeps a wall's normal velocity zero; the projection again
        // resets a prescribed velocity.
        TimerOutput::Scope t(timer, "side walls");
        weights->map_phase(side_walls);
        side_walls.apply(nodal.mass,
                         nodal.velocity_new,
                         weights->active_dofs(),
                         dt);
        boundary_conditions.project_velocity(
          nodal.velocity_new, BoundaryConditions<dim>::Contact::as_last_update);
      }
    if (pore_water.active())
      pore_water.finish_velocity(nodal,
                                 weights->active_dofs(),
                                 boundary_conditions);
    // The acceleration consistent with the constrained velocity change
    // from u, so that the FLIP update of the points respects the
    // constraints too.
    for_each_active_dof([&](const unsigned int i) {
      nodal.acceleration.local_element(i) =
        (nodal.velocity_new.local_element(i) - brought_velocity(i)) / dt;
    });
  }


  template <int dim>
  template <typename Body>
  void
  Simulator<dim>::for_each_active_dof(const Body &body) const
  {
    // Entry by entry, each on its own: the same numbers on any number of
    // threads.
    const std::vector<unsigned int> &dofs = weights->active_dofs();
    for_each_chunk(dofs.size(),
                   8 * chunk_size_for(dofs.size()),
                   [&](const unsigned int,
                       const unsigned int first,
                       const unsigned int last) {
                     for (unsigned int j = first; j < last; ++j)
                       body(dofs[j]);
                   });
  }


  // The members defined here (the class itself is instantiated in
  // simulator.cc): one explicit instantiation per member, so that
  // the Simulator's files can share one translation unit (unity
  // build) without instantiating the class twice.
#define MPM_INSTANTIATE(dim)                                           \
  template void Simulator<dim>::compute_nodal_velocity(NodalVector &); \
  template void Simulator<dim>::update_nodal_kinematics();

  MPM_INSTANTIATE(2)
  MPM_INSTANTIATE(3)
#undef MPM_INSTANTIATE
} // namespace MPM

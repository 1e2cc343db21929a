// The Simulator's core: construction, the run loop and the time step as
// the algorithm's sequence of stages (doc/algorithm.md). Its other
// concerns are in simulator_setup.cc (the set-up of a run),
// simulator_parameters.cc (the parameter file),
// simulator_checkpoint.cc (checkpoints, restart, repartitioning),
// simulator_diagnostics.cc (statistics, energies, blow-up detection),
// simulator_nodal_update.cc (the nodal steps between the particle-grid
// passes) and simulator_report.cc (the end of a run).

#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <mpm/solver/simulator.h>

#include <chrono>
#include <iomanip>

namespace MPM
{
  template <int dim>
  Simulator<dim>::Simulator(const MPI_Comm comm)
    : mpi_communicator(comm)
    , pcout(std::cout, Utilities::MPI::this_mpi_process(comm) == 0)
    , grid(comm)
    , point_update(materials, transfer, point_relocation, time_stepping)
    , nonlocal_averaging(materials)
    // Rank 0's own timings: with MPI_COMM_SELF the timer does not try to
    // synchronise in its destructor when an input error unwinds the stack.
    , timer(MPI_COMM_SELF, pcout, TimerOutput::never, TimerOutput::wall_times)
  {}


  template <int dim>
  Simulator<dim>::~Simulator() = default;


  template <int dim>
  void
  Simulator<dim>::setup_nodal_fields()
  {
    const auto partitioner = std::make_shared<Utilities::MPI::Partitioner>(
      grid.locally_owned_dofs, grid.locally_relevant_dofs, mpi_communicator);
    nodal.reinit(partitioner);
    // The nodal-vector entries of every cell's vertices, looked up once:
    // the DoF handler and the partitioner's global-to-local map are not
    // touched by the steps.
    cell_dofs.reinit(grid, *partitioner);
    periodic_nodes.reinit(
      grid.periodic_boundaries.node_groups(grid.dof_handler,
                                           grid.locally_relevant_dofs),
      *partitioner);
    boundary_conditions.setup(grid, nodal.mass, &periodic_nodes);
    point_relocation.initialize(grid);
    point_relocation.set_walls(boundary_conditions.constrained_boundary_ids());
    weights->setup_partition();
  }


  template <int dim>
  double
  Simulator<dim>::compute_time_step() const
  {
    double dt = time_stepping.fixed_time_step;
    Assert(max_point_speed_step == step,
           ExcMessage("The time step of step " + std::to_string(step) +
                      " needs the points' largest speed at its start, which "
                      "the grid-to-particle pass of the step before sets; "
                      "it was set for step " +
                      std::to_string(max_point_speed_step) + "."));
    // The fastest wave of the components that bound the step.
    const double fastest_wave = time_step_bounds.max_wave_speed();
    if (time_stepping.adaptive)
      dt = std::min(time_stepping.maximum_time_step,
                    time_stepping.cfl_number * active_cell_size /
                      (fastest_wave + max_point_speed));
    // Land on the end time exactly rather than overshoot it.
    if (time + dt > effective_end_time(time_stepping.end_time))
      dt = time_stepping.end_time - time;
    return dt;
  }


  template <int dim>
  void
  Simulator<dim>::relocate_points()
  {
    TimerOutput::Scope t(timer, "locate points");
    const auto n_lost_before = lost_points.n_local();
    if (point_relocation.can_locate_while_moving())
      // Step 1 was done by update_points_from_grid().
      point_relocation.relocate_leavers(particle_handler);
    else
      point_relocation.relocate(particle_handler);
    lost_points.check(n_lost_before, step, time, mpi_communicator, pcout);
  }


  template <int dim>
  void
  Simulator<dim>::do_time_step()
  {
    // The strength of this step (a strength reduction factor that
    // depends on time).
    materials.set_time(time);
    prepare_transfer();
    if (boundary_conditions.contact_by_gap())
      {
        // Where the material touches the frictional walls (WallGap).
        TimerOutput::Scope t(timer, "wall contact");
        boundary_conditions.find_contact(
          particle_handler,
          [this](const double *props, const Tensor<1, dim> &n) {
            return weights->reach_along(props, n);
          });
      }
    time_step = compute_time_step();
    point_update.set_time_step(time_step);
    if (pore_water.active())
      pore_water.set_step(time_step,
                          transfer.scheme().flip_fraction(time_step),
                          time_stepping.gravity);
    time_stepping.step_scheme->advance(*this);
    // For the next step's time step, like the largest point speed.
    if (materials.has_state_dependent_stiffness())
      max_state_wave_speed = Utilities::MPI::max(
        point_update.take_max_state_wave_speed(), mpi_communicator);
    time += time_step;
    ++step;
    relocate_points();
  }


  template <int dim>
  void
  Simulator<dim>::map_mass_and_momentum(const bool with_forces)
  {
    weights->map_mass_and_momentum(with_forces);
  }


  template <int dim>
  void
  Simulator<dim>::map_forces()
  {
    weights->map_forces();
  }


  template <int dim>
  NodalVector &
  Simulator<dim>::nodal_velocity(const NodalVelocity which)
  {
    return which == NodalVelocity::brought ? nodal.velocity :
                                             nodal.velocity_new;
  }


  template <int dim>
  void
  Simulator<dim>::compute_nodal_velocity(const NodalVelocity target)
  {
    compute_nodal_velocity(nodal_velocity(target));
  }


  template <int dim>
  void
  Simulator<dim>::update_stress(const NodalVelocity source,
                                const bool          set_affine)
  {
    average_nonlocal_variables();
    weights->update_stress(nodal_velocity(source), set_affine);
  }


  template <int dim>
  void
  Simulator<dim>::filter_brought_velocity()
  {
    if (!transfer.scheme().filters_brought_velocity())
      return;
    TimerOutput::Scope t(timer, "transfer filter");
    transfer.scheme().filter_brought_velocity(*weights,
                                              boundary_conditions,
                                              nodal);
  }


  template <int dim>
  void
  Simulator<dim>::update_points_from_grid(const bool remap_momentum)
  {
    if (pore_water.active())
      {
        // Under the weights of the step, before the skeleton's update
        // moves the points.
        TimerOutput::Scope t(timer, "pore water");
        pore_water.set_skeleton_velocity(nodal.velocity_new);
        weights->update_phase_points(pore_water);
        if (NodalPressureRate<dim> *rate = pore_water.nodal_pressure_rate())
          {
            // The pressures from the points' rates averaged at the nodes.
            weights->map_phase(*rate);
            rate->compute_nodal_rates(weights->active_dofs());
            weights->update_phase_points(*rate);
          }
      }
    set_max_point_speed(weights->update_points_from_grid(remap_momentum));
  }


  template <int dim>
  bool
  Simulator<dim>::has_affine_transfer() const
  {
    return transfer.scheme().carries_affine_velocity();
  }


  template <int dim>
  void
  Simulator<dim>::average_nonlocal_variables()
  {
    if (!nonlocal_averaging.active())
      return;
    TimerOutput::Scope t(timer, "nonlocal averaging");
    nonlocal_averaging.update(particle_handler, mpi_communicator);
  }


  template <int dim>
  void
  Simulator<dim>::prepare_transfer()
  {
    active_cell_size =
      Utilities::MPI::min(weights->begin_step(nodal), mpi_communicator);
  }


  template <int dim>
  void
  Simulator<dim>::write_output(const bool force)
  {
    if (!force &&
        !output_writer.output_due(time, time_step, time_stepping.end_time))
      return;
    TimerOutput::Scope t(timer, "output");
    output_writer.mark_written(time);
    output_writer.write_particles(particle_handler,
                                  point_properties.names(),
                                  time,
                                  output_index++,
                                  mpi_communicator);
    const auto s = compute_statistics();
    // Collective: every rank takes part, only rank 0 writes.
    const auto removed = lost_points.totals(mpi_communicator);
    statistics_file.write_row(
      {s, removed.n_points, removed.mass, grid.get_local_origin()});
  }


  template <int dim>
  void
  Simulator<dim>::run()
  {
    const auto wall_start = std::chrono::steady_clock::now();
    setup();
    output_writer.write_mesh(grid);
    // A resumed run's postprocessors read their state from the checkpoint
    // and its output at the checkpoint's time was written before.
    if (!checkpointing.resume())
      {
        for (auto &p : postprocessors)
          p->initialize();
        write_output(true);
      }
    unsigned int steps_this_run = 0;

    double last_progress = 0;
    auto   wall_seconds  = [&]() {
      return std::chrono::duration<double>(std::chrono::steady_clock::now() -
                                           wall_start)
        .count();
    };
    // The throughput counts the steps only, not the set-up.
    const double steps_start = wall_seconds();
    // The end time, or rest before it ('Termination/Stop at rest').
    auto finished = [&]() {
      return time_stepping.reached_end(time) || rest_criterion.at_rest();
    };
    while (!finished())
      {
        do_time_step();
        if (rest_criterion.enabled())
          rest_criterion.update(time, point_speed(rest_criterion.measure()));
        if (stability_monitor.energy_check_due(step))
          {
            const std::string problem =
              stability_monitor.check_energy(compute_statistics());
            if (!problem.empty())
              stop_on_blow_up(problem, false);
          }
        if (load_balancing.repartition_due(step,
                                           particle_handler,
                                           mpi_communicator))
          repartition();
        // The last step is an output step, whether it ends at the end time
        // or at rest.
        const bool output_step =
          rest_criterion.at_rest() ||
          output_writer.output_due(time, time_step, time_stepping.end_time);
        for (auto &p : postprocessors)
          p->execute(output_step);
        write_output(rest_criterion.at_rest());
        ++steps_this_run;
        if (!finished() && checkpointing.due(steps_this_run, mpi_communicator))
          write_checkpoint();
        if (checkpointing.stop_requested(steps_this_run) && !finished())
          {
            pcout << "Stopped after " << steps_this_run
                  << " steps of this run (Checkpointing/Stop after steps) at "
                     "step "
                  << step << ", t = " << time
                  << " s; continue with 'Checkpointing/Resume from "
                     "checkpoint = true'. No report is written.\n";
            timer.print_summary();
            return;
          }

        const double wall = wall_seconds();
        if (wall - last_progress >= output_writer.progress_interval() ||
            finished())
          {
            last_progress         = wall;
            const double fraction = time / time_stepping.end_time;
            pcout << "step " << std::setw(7) << step << "  t = " << std::setw(11)
                  << std::setprecision(5) << time << " s  dt = " << std::setw(10)
                  << time_step << " s  wall " << std::setprecision(3) << wall
                  << " s  remaining ~" << wall * (1 - fraction) / fraction
                  << " s" << std::endl;
          }
      }

    output_writer.write_point_file(particle_handler,
                                   materials,
                                   grid,
                                   mpi_communicator);
    write_report();
    const double wall = wall_seconds();
    print_run_summary(wall, wall - steps_start, steps_this_run);
  }


  template class Simulator<2>;
  template class Simulator<3>;
} // namespace MPM

// The set-up of a run, in the order its parts depend on each other: the
// scene (mesh, gravity, walls, phases), the nodal fields, the points'
// property slots, the points themselves (generated, or read from a
// checkpoint), and what the first step needs of them.

#include <mpm/base/input_error.h>
#include <mpm/material_points/property_layout.h>
#include <mpm/parallel/thread_chunks.h>
#include <mpm/solver/simulator.h>

#include <fstream>
#include <iomanip>
#include <sstream>

namespace MPM
{
  template <int dim>
  void
  Simulator<dim>::setup()
  {
    TimerOutput::Scope   t(timer, "setup");
    const OneThreadScope one_thread;
    setup_scene();
    setup_time_step_bounds();
    setup_nodal_fields();
    setup_point_properties();
    const std::string state = create_points();

    const auto stats = compute_statistics();
    max_point_speed  = stats.max_speed;
    if (materials.has_state_dependent_stiffness())
      max_state_wave_speed = compute_max_state_wave_speed();
    stability_monitor.initialize(stats, boundary_conditions.does_work());
    if (checkpointing.resume())
      {
        deserialize_state(state);
        max_point_speed_step = step;
        pcout << "Resumed from the checkpoint at step " << step
              << ", t = " << time << " s\n";
      }
    pcout << "dealii-mpm: " << dim << "D, "
          << grid.triangulation.n_global_active_cells() << " cells, "
          << stats.n_points << " material points, mass " << stats.mass
          << " kg, " << Utilities::MPI::n_mpi_processes(mpi_communicator)
          << " MPI rank(s) x " << one_thread.threads_outside()
          << " thread(s)\n";

    if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
      {
        // Every run keeps the parameters it ran with beside its results.
        std::ofstream(output_writer.directory() + "parameters.prm")
          << parameters_text;
        // Resumed: the lines written after the checkpoint (by the run that
        // stopped or crashed) are dropped; they will be written again.
        statistics_file.open(output_writer.directory() + "statistics",
                             checkpointing.resume(),
                             statistics_length,
                             pore_water.active());
      }
  }


  template <int dim>
  void
  Simulator<dim>::setup_scene()
  {
    output_writer.initialize(mpi_communicator);
    grid.create();
    // Gravity is given in the scene's frame, like everything else.
    time_stepping.gravity = grid.to_mesh_frame(time_stepping.scene_gravity);
    boundary_conditions.check_boundary_ids(grid);
    boundary_conditions.set_gravity(time_stepping.gravity);
    // Before the nodal fields are laid out: the water's are among them.
    pore_water.initialize(materials, nodal);
    boundary_conditions.set_pore_water(pore_water.active());
    pore_water.set_skeleton_transfer(
      transfer.scheme().carries_affine_velocity());
    if (pore_water.active() &&
        boundary_conditions.has_frictional_wall_without_memory() &&
        (pore_water.affine_transfer() ||
         transfer.scheme().flip_fraction(1e-6) > 0))
      pcout << "Warning: saturated materials on a frictional wall without "
               "a 'Normal stress memory length', their water transferred "
               "with a FLIP share ('Transfer/Scheme = flip/pic blend') or "
               "as APIC ('Pore water/Water velocity transfer = affine'): "
               "nothing damps the flutter of Coulomb friction, which pumps "
               "the pore pressure (a saturated layer sliding on a Coulomb "
               "bed: 31 % slow with the blend 0.98 at CFL 0.5, stopped with "
               "the affine water at CFL 0.3 and above; exact at CFL 0.5 "
               "with a memory of 1 mm; doc/boundary_conditions.md, "
               "'Sliding on Coulomb friction: a flutter').\n";
    // Local damping (the quasi-static strength-reduction files) drains
    // what the pairing feeds in until a layer runs far past failure.
    if (time_stepping.volumetric_strain_averaging !=
          TimeSteppingParameters<dim>::VolumetricStrainAveraging::none &&
        transfer.scheme().flip_fraction(1e-6) > 0 &&
        time_stepping.local_damping == 0 &&
        !time_stepping.local_damping_function)
      pcout << "Warning: 'Time stepping/Volumetric strain averaging = cell' "
               "(the default) or 'patch' with a FLIP share ('Transfer/FLIP "
               "fraction' > 0): the stress update takes an averaged volumetric "
               "rate "
               "while the forces take each point's own stress, and FLIP, "
               "which does not damp, was measured to gain energy from that "
               "once the material flows (an elastic wedge down the flume "
               "stopped by the energy check within 0.6 s; a dilating "
               "infinite slope; doc/convergence.md, 'Defaults'). Set "
               "'Volumetric strain averaging = none' with FLIP, or use the "
               "default 'Transfer/Scheme = apic'.\n";
    side_walls.initialize(nodal);
    if (!pore_water.active())
      for (const std::string &name :
           boundary_conditions.pore_pressure_boundaries())
        throw InputError("Boundary conditions/" + name +
                         "/Pore pressure is set, but no material is "
                         "saturated (Porosity > 0): there is no pore water "
                         "for it to act on.");
  }


  template <int dim>
  void
  Simulator<dim>::setup_time_step_bounds()
  {
    time_step_bounds.clear();
    // The materials' P waves. With a state-dependent stiffness (Cam-Clay),
    // those materials' wave speed is the largest over their points at the
    // start of the step.
    time_step_bounds.add([this]() {
      return materials.has_state_dependent_stiffness() ?
               std::max(materials.max_constant_wave_speed(),
                        max_state_wave_speed) :
               materials.max_wave_speed();
    });
    // A viscous stress (MaterialModel::maximum_viscosity()): the explicit
    // diffusion bound dt <= h^2 / (2 d nu), as the speed 2 d nu / h of the
    // CFL condition (at CFL <= 1 the step stays below the bound).
    if (materials.max_kinematic_viscosity() > 0)
      time_step_bounds.add([this]() {
        return 2. * dim * materials.max_kinematic_viscosity() /
               active_cell_size;
      });
    // The pore water's: the two phases' fast P wave
    // (PoreWater::fastest_wave_speed()).
    if (pore_water.active())
      time_step_bounds.add(
        [this]() { return pore_water.max_wave_speed(materials); });
  }


  template <int dim>
  void
  Simulator<dim>::setup_point_properties()
  {
    // The points' slots: the fixed ones, the material state, then the
    // transfer scheme's own (APIC's C_p), then the weights' (CPDI's
    // domain).
    point_properties.reset(PropertyLayout<dim>::fixed_names());
    point_properties.add("material state", state_variable_names());
    AssertThrow(transfer.scheme().point_property_names().size() ==
                    transfer.scheme().n_point_properties() &&
                  weights->point_property_names().size() ==
                    weights->n_point_properties(),
                ExcInternalError());
    transfer_slot =
      point_properties.add("transfer scheme",
                           transfer.scheme().point_property_names());
    const unsigned int weights_slot =
      point_properties.add("particle-grid weights",
                           weights->point_property_names());
    weights->set_property_slots(transfer_slot, weights_slot);
    if (pore_water.active())
      {
        pore_water.set_first_slot(
          point_properties.add("pore water",
                               pore_water.point_property_names()));
        point_update.set_porosity_slot(pore_water.porosity_slot());
      }
    particle_handler.initialize(grid.triangulation,
                                grid.mapping,
                                point_properties.n_slots());
    load_balancing.connect(grid.triangulation, particle_handler);
    // What a removed point takes away, so that the energy check compares
    // the remaining points with what remains available to them.
    lost_points.connect(particle_handler,
                        [this](const double *props, const Point<dim> &x) {
                          return energy_of_point(props, x);
                        });
  }


  template <int dim>
  std::string
  Simulator<dim>::create_points()
  {
    std::string state;
    if (checkpointing.resume())
      {
        // The mesh with its partition and the points as they were.
        state = checkpointing.read(grid.triangulation,
                                   particle_handler,
                                   point_properties.names());
        grid.setup_partition_data();
        setup_nodal_fields();
      }
    else
      for (const auto &region : point_generator.generate(
             grid,
             materials,
             time_stepping.scene_gravity,
             particle_handler,
             transfer.scheme().carries_affine_velocity() ?
               transfer_slot :
               numbers::invalid_unsigned_int,
             pore_water.initial_state()))
        pcout << "Region '" << region.name << "': " << region.n_points
              << " material points, volume " << region.volume
              << (dim == 2 ? " m^2" : " m^3") << ", mass " << region.mass
              << (dim == 2 ? " kg/m\n" : " kg\n");
    if (!checkpointing.resume() && pore_water.active())
      pore_water.initialize_points(particle_handler, grid);
    if (grid.get_local_origin().norm() > 0)
      pcout << "Local origin (Mesh/Local origin): " << std::setprecision(12)
            << grid.get_local_origin() << std::setprecision(6)
            << " m: the mesh and the VTU files are at x minus it; the "
               "parameter file, the statistics and the rasters in map "
               "coordinates\n";
    // Checked on a resumed run too: its report is that of an
    // uninterrupted run.
    for (const auto &region : point_generator.regions_beyond_mesh(
           grid, boundary_conditions.constrained_boundary_ids()))
      {
        std::ostringstream warning;
        warning << std::setprecision(6);
        warning << "the region 'Material points/" << region.name
                << "' reaches beyond the mesh through " << region.crossed_area
                << (dim == 2 ? " m" : " m^2")
                << " of a boundary that no boundary condition holds: the "
                   "material it describes beyond the mesh is not created";
        if (region.volume_lost >= 0)
          warning << " (" << region.volume_lost << (dim == 2 ? " m^2" : " m^3")
                  << " of the region)";
        warning << ". Enlarge the mesh or the region's limits.";
        warnings.push_back(warning.str());
        pcout << "Warning: " << warning.str() << '\n';
      }
    // p4est's first partition balances cells; the work is where the points
    // are.
    if (!checkpointing.resume() &&
        Utilities::MPI::n_mpi_processes(mpi_communicator) > 1)
      repartition();

    if (!checkpointing.resume() && transfer.scheme().initializes_points())
      {
        // Under the first step's weights.
        prepare_transfer();
        transfer.scheme().initialize_points(*weights, transfer_slot);
      }
    return state;
  }


  // The members defined here (the class itself is instantiated in
  // simulator.cc): one explicit instantiation per member, so that
  // the Simulator's files can share one translation unit (unity
  // build) without instantiating the class twice.
#define MPM_INSTANTIATE(dim)                                     \
  template void        Simulator<dim>::setup();                  \
  template void        Simulator<dim>::setup_scene();            \
  template void        Simulator<dim>::setup_time_step_bounds(); \
  template void        Simulator<dim>::setup_point_properties(); \
  template std::string Simulator<dim>::create_points();

  MPM_INSTANTIATE(2)
  MPM_INSTANTIATE(3)
#undef MPM_INSTANTIATE
} // namespace MPM

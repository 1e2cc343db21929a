#include <deal.II/base/mpi.h>
#include <deal.II/grid/grid_tools.h>

#include <boost/archive/binary_iarchive.hpp>
#include <boost/archive/binary_oarchive.hpp>
#include <boost/serialization/string.hpp>
#include <boost/serialization/utility.hpp>
#include <boost/serialization/vector.hpp>

#include <chrono>
#include <filesystem>

#include <mpm/base/input_deck.h>
#include <mpm/base/input_error.h>
#include <mpm/material_points/property_layout.h>
#include <mpm/solver/simulator.h>
#include <mpm/transfer/velocity_transfer.h>

#include <chrono>
#include <iomanip>
#include <limits>
#include <sstream>

namespace MPM
{
  template <int dim>
  void
  Simulator<dim>::declare_name_lists(ParameterHandler &prm)
  {
    prm.declare_entry("Dimension",
                      "2",
                      Patterns::Integer(2, 3),
                      "Spatial dimension of the scene.");
    MaterialLibrary::declare_name_list(prm);
    PointGenerator<dim>::declare_name_list(prm);
    BoundaryConditions<dim>::declare_name_list(prm);
  }


  template <int dim>
  typename Simulator<dim>::NameLists
  Simulator<dim>::read_name_lists(ParameterHandler &prm)
  {
    NameLists names;
    names.materials  = MaterialLibrary::read_name_list(prm);
    names.regions    = PointGenerator<dim>::read_name_list(prm);
    names.boundaries = BoundaryConditions<dim>::read_name_list(prm);
    return names;
  }


  template <int dim>
  void
  Simulator<dim>::declare_parameters(ParameterHandler &prm,
                                     const NameLists  &names)
  {
    prm.declare_entry("Dimension",
                      "2",
                      Patterns::Integer(2, 3),
                      "Spatial dimension of the scene.");
    BackgroundGrid<dim>::declare_parameters(prm);
    MaterialLibrary::declare_parameters(prm, names.materials);
    PointGenerator<dim>::declare_parameters(prm, names.regions);
    prm.enter_subsection("Material points");
    prm.declare_entry("Points leaving the mesh",
                      "error",
                      Patterns::Selection("error|remove"),
                      "What happens to a material point that leaves the "
                      "mesh: 'error' stops the run naming the point; "
                      "'remove' removes it, and the number of removed points "
                      "and their mass are reported in the statistics file "
                      "and at the end of the run.");
    prm.leave_subsection();
    PointRelocation<dim>::declare_parameters(prm);
    BoundaryConditions<dim>::declare_parameters(prm, names.boundaries);
    TimeSteppingParameters<dim>::declare_parameters(prm);
    VelocityTransfer<dim>::declare_parameters(prm);
    ParticleGridWeights<dim>::declare_parameters(prm);
    OutputWriter<dim>::declare_parameters(prm);
    LoadBalancing<dim>::declare_parameters(prm);
    Checkpointing<dim>::declare_parameters(prm);
    StabilityMonitor<dim>::declare_parameters(prm);
    prm.enter_subsection("Postprocess");
    prm.declare_entry("List of postprocessors",
                      "",
                      Patterns::MultipleSelection(Postprocessors::names()),
                      "Comparisons with references that are run during the "
                      "simulation and written to report.txt in the output "
                      "directory.");
    prm.leave_subsection();
    Postprocessors::declare_parameters<dim>(prm);
  }


  template <int dim>
  Simulator<dim>::Simulator(const MPI_Comm comm)
    : mpi_communicator(comm)
    , pcout(std::cout, Utilities::MPI::this_mpi_process(comm) == 0)
    , grid(comm)
    , point_update(materials, transfer, point_relocation, time_stepping)
    // Rank 0's own timings: with MPI_COMM_SELF the timer does not try to
    // synchronise in its destructor when an input error unwinds the stack.
    , timer(MPI_COMM_SELF, pcout, TimerOutput::never, TimerOutput::wall_times)
  {}


  template <int dim>
  Simulator<dim>::~Simulator() = default;


  template <int dim>
  void
  Simulator<dim>::parse_parameters(ParameterHandler  &prm,
                                   const std::string &input_dir)
  {
    input_directory = input_dir;
    std::ostringstream all_parameters;
    prm.print_parameters(all_parameters, ParameterHandler::ShortPRM);
    parameters_text = all_parameters.str();
    grid.parse_parameters(prm, input_directory);
    materials.parse_parameters(prm);
    point_generator.parse_parameters(prm, materials, input_directory);
    prm.enter_subsection("Material points");
    error_on_lost_points = prm.get("Points leaving the mesh") == "error";
    prm.leave_subsection();
    point_relocation.parse_parameters(prm);
    boundary_conditions.parse_parameters(prm);
    time_stepping.parse_parameters(prm);
    transfer.parse_parameters(prm);
    transfer.scheme().add_nodal_fields(nodal);
    weights = ParticleGridWeights<dim>::create(
      prm,
      TransferContext<dim>{particle_handler,
                           grid,
                           nodal,
                           transfer,
                           point_update,
                           time_stepping,
                           step,
                           time_step,
                           local_dofs_of_cells,
                           timer});
    prm.enter_subsection("Transfer");
    const bool linear_weights = prm.get("Particle-grid weights") == "linear";
    prm.leave_subsection();
    if (transfer.apic() != nullptr &&
        time_stepping.scheme != UpdateScheme::musl && linear_weights)
      pcout << "Warning: 'Transfer/Scheme = apic' with 'Time stepping/Update "
               "scheme' USF or USL fits each point's affine matrix to the "
               "end-of-step grid velocity, which on bilinear cells was "
               "measured unstable above CFL 0.05 (doc/transfers.md); MUSL "
               "takes it from the MUSL remap and is stable, and so are CPDI "
               "weights ('Transfer/Particle-grid weights = cpdi').\n";
    output_writer.parse_parameters(prm);
    load_balancing.parse_parameters(prm);
    stability_monitor.parse_parameters(prm);
    checkpointing.parse_parameters(prm, output_writer.directory());
    prm.enter_subsection("Postprocess");
    postprocessor_names = split_name_list(prm.get("List of postprocessors"),
                                          "Postprocess/List of postprocessors");
    prm.leave_subsection();
    for (const auto &name : postprocessor_names)
      postprocessors.push_back(Postprocessors::create<dim>(name, prm));
  }


  template <int dim>
  std::vector<std::string>
  Simulator<dim>::property_names() const
  {
    auto names = PropertyLayout<dim>::fixed_names();
    // The state slots: named by the model if there is one material,
    // generically otherwise.
    const unsigned int n_state = materials.max_n_state_variables();
    const auto model_names = materials[0].model->state_variable_names();
    for (unsigned int i = 0; i < n_state; ++i)
      names.push_back(materials.size() == 1 && i < model_names.size() ?
                        model_names[i] :
                        "state_" + std::to_string(i));
    for (const auto &name : transfer.scheme().point_property_names())
      names.push_back(name);
    for (const auto &name : weights->point_property_names())
      names.push_back(name);
    return names;
  }


  template <int dim>
  void
  Simulator<dim>::setup()
  {
    TimerOutput::Scope t(timer, "setup");
    output_writer.initialize(mpi_communicator);
    grid.create();
    boundary_conditions.check_boundary_ids(grid);
    boundary_conditions.set_gravity(time_stepping.gravity);

    setup_nodal_fields();

    // The material state, then the transfer scheme's own slots (APIC's
    // C_p), then the weights' (CPDI's domain).
    transfer_slot =
      PropertyLayout<dim>::state + materials.max_n_state_variables();
    const unsigned int weights_slot =
      transfer_slot + transfer.scheme().n_point_properties();
    weights->set_property_slots(transfer_slot, weights_slot);
    particle_handler.initialize(grid.triangulation,
                                grid.mapping,
                                weights_slot + weights->n_point_properties());
    load_balancing.connect(grid.triangulation, particle_handler);
    particle_handler.signals.particle_lost.connect(
      [this](const typename Particles::ParticleIterator<dim> &particle,
             const typename Triangulation<dim>::active_cell_iterator &) {
        const double *props = particle->get_properties().data();
        const double  mass  = props[PropertyLayout<dim>::mass];
        ++n_lost_points;
        lost_mass += mass;
        // The energy it takes away, so that the energy check compares the
        // remaining points with what remains available to them.
        const auto energy = energy_of_point(props, particle->get_location());
        lost_energy += energy[0] + energy[1] + energy[2];
        std::ostringstream s;
        s << "material point " << particle->get_id() << " (mass " << mass
          << " kg) left the mesh at (" << particle->get_location() << ")";
        lost_point_descriptions.push_back(s.str());
      });
    std::string state;
    if (checkpointing.resume())
      {
        // The mesh with its partition and the points as they were.
        state = checkpointing.read(grid.triangulation, particle_handler);
        grid.setup_partition_data();
        setup_nodal_fields();
      }
    else
      point_generator.generate(grid,
                               materials,
                               time_stepping.gravity,
                               particle_handler,
                               transfer.apic() != nullptr ?
                                 transfer_slot :
                                 numbers::invalid_unsigned_int);
    // Checked on a resumed run too: its report is that of an
    // uninterrupted run.
    for (const auto &region : point_generator.regions_beyond_mesh(
             grid, boundary_conditions.constrained_boundary_ids()))
        {
          std::ostringstream warning;
          warning << std::setprecision(6);
          warning << "the region 'Material points/" << region.name
                  << "' reaches beyond the mesh through "
                  << region.crossed_area << (dim == 2 ? " m" : " m^2")
                  << " of a boundary that no boundary condition holds: the "
                     "material it describes beyond the mesh is not created";
          if (region.volume_lost >= 0)
            warning << " (" << region.volume_lost
                    << (dim == 2 ? " m^2" : " m^3") << " of the region)";
          warning << ". Enlarge the mesh or the region's limits.";
          warnings.push_back(warning.str());
          pcout << "Warning: " << warning.str() << '\n';
        }
    // Gravity is given in the scene's frame, like everything else.
    time_stepping.gravity = grid.to_mesh_frame(time_stepping.gravity);
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

    const auto stats = compute_statistics();
    max_point_speed  = stats.max_speed;
    stability_monitor.initialize(stats, boundary_conditions.does_work());
    if (checkpointing.resume())
      {
        deserialize_state(state);
        pcout << "Resumed from the checkpoint at step " << step
              << ", t = " << time << " s\n";
      }
    pcout << "dealii-mpm: " << dim << "D, "
          << grid.triangulation.n_global_active_cells() << " cells, "
          << stats.n_points << " material points, mass " << stats.mass
          << " kg, " << Utilities::MPI::n_mpi_processes(mpi_communicator)
          << " MPI rank(s)\n";

    if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
      {
        // Every run keeps the parameters it ran with beside its results.
        std::ofstream(output_writer.directory() + "parameters.prm")
          << parameters_text;
        if (checkpointing.resume())
          {
            // Lines written after the checkpoint (by the run that stopped
            // or crashed) are dropped: they will be written again.
            const std::string name = output_writer.directory() + "statistics";
            if (std::filesystem::exists(name) &&
                std::filesystem::file_size(name) > statistics_length)
              std::filesystem::resize_file(name, statistics_length);
            statistics_file.open(name, std::ios::app);
          }
        else
          statistics_file.open(output_writer.directory() + "statistics");
        if (!checkpointing.resume())
          statistics_file
          << "# Columns: 1 time (s), 2 step, 3 time step (s), 4 points, 5 "
             "mass (kg), "
          << 6 << "-" << 5 + dim << " momentum (kg m/s), " << 6 + dim
          << " kinetic energy (J), " << 7 + dim << " strain energy (J), "
          << 8 + dim << " gravitational potential energy (J), " << 9 + dim
          << " mean speed (m/s), " << 10 + dim << "-" << 9 + 2 * dim
          << " centre of mass (m), " << 10 + 2 * dim
          << " removed points, " << 11 + 2 * dim
          << " removed mass (kg). Energies per unit thickness in 2D.\n";
      }
  }


  template <int dim>
  void
  Simulator<dim>::setup_nodal_fields()
  {
    const auto partitioner = std::make_shared<Utilities::MPI::Partitioner>(
      grid.locally_owned_dofs, grid.locally_relevant_dofs, mpi_communicator);
    nodal.reinit(partitioner);
    // The nodal-vector entries of every locally owned cell's vertices,
    // looked up once: the DoF handler and the partitioner's global-to-local
    // map are not touched by the steps.
    using DoFCellIterator = typename DoFHandler<dim>::active_cell_iterator;
    std::vector<types::global_dof_index> cell_dofs(grid.fe.n_dofs_per_cell());
    local_dofs_of_cells.assign(grid.triangulation.n_active_cells(), {});
    for (const auto &tria_cell : grid.triangulation.active_cell_iterators())
      // Ghost cells too: CPDI's domains reach into them.
      if (!tria_cell->is_artificial())
        {
          const DoFCellIterator cell(&grid.triangulation,
                                     tria_cell->level(),
                                     tria_cell->index(),
                                     &grid.dof_handler);
          cell->get_dof_indices(cell_dofs);
          auto &local = local_dofs_of_cells[tria_cell->active_cell_index()];
          for (const unsigned int v : cell->vertex_indices())
            for (unsigned int c = 0; c < dim; ++c)
              local[v][c] = partitioner->global_to_local(
                cell_dofs[grid.fe.component_to_system_index(c, v)]);
        }
    boundary_conditions.setup(grid, nodal.mass);
    point_relocation.initialize(grid);
    weights->setup_partition();
  }


  namespace
  {
    std::string
    join(const std::vector<std::string> &names)
    {
      std::string joined;
      for (const auto &n : names)
        joined += (joined.empty() ? "" : ", ") + n;
      return joined;
    }
  } // namespace


  template <int dim>
  std::string
  Simulator<dim>::serialize_state() const
  {
    // Collective parts first: every rank computes the same state.
    const types::particle_index removed_points =
      Utilities::MPI::sum(n_lost_points, mpi_communicator);
    const double removed_mass = Utilities::MPI::sum(lost_mass, mpi_communicator);
    const double removed_energy =
      Utilities::MPI::sum(lost_energy, mpi_communicator);
    const std::uint64_t n_points    = particle_handler.n_global_particles();
    const std::uint64_t n_cells     = grid.triangulation.n_global_active_cells();
    // 2: the removed points' energy appended; 3: the walls' contact state
    // (formats 1 and 2 are still read).
    const unsigned int  format      = 3;
    const unsigned int  space_dim   = dim;
    std::uint64_t       stats_bytes = 0;
    if (statistics_file.is_open())
      stats_bytes = const_cast<std::ofstream &>(statistics_file).tellp();
    stats_bytes = Utilities::MPI::broadcast(mpi_communicator, stats_bytes, 0);

    std::vector<std::string> postprocessor_states;
    for (const auto &p : postprocessors)
      {
        std::ostringstream out;
        p->save_state(out);
        postprocessor_states.push_back(out.str());
      }

    const auto contact = BoundaryConditions<dim>::merge(
      Utilities::MPI::all_gather(mpi_communicator,
                                 boundary_conditions.contact_locations()));

    std::ostringstream state;
    {
      boost::archive::binary_oarchive ar(state);
      ar << format << space_dim << n_points << n_cells << time << step
         << time_step << output_index << max_point_speed << removed_points
         << removed_mass << n_repartitions << stats_bytes << output_writer
         << postprocessor_names << postprocessor_states << removed_energy
         << contact[0] << contact[1];
    }
    return state.str();
  }


  template <int dim>
  void
  Simulator<dim>::deserialize_state(const std::string &state)
  {
    std::istringstream in(state);
    boost::archive::binary_iarchive ar(in);
    unsigned int  format = 0, space_dim = 0;
    std::uint64_t n_points = 0, n_cells = 0;
    types::particle_index removed_points = 0;
    double                removed_mass   = 0;
    double                removed_energy = 0;
    std::vector<std::string> names, postprocessor_states;
    ar >> format >> space_dim >> n_points >> n_cells;
    check_input(format >= 1 && format <= 3 && space_dim == dim,
                std::string("The checkpoint was written by another version "
                           "of dealii-mpm or for another dimension."));
    check_input(n_cells == grid.triangulation.n_global_active_cells(),
                std::string("The checkpoint's mesh has " +
                           std::to_string(n_cells) +
                           " cells, the mesh of the parameters " +
                           std::to_string(
                             grid.triangulation.n_global_active_cells()) +
                           ": resume with the parameters of the run."));
    check_input(n_points == particle_handler.n_global_particles(),
                std::string("The checkpoint holds " + std::to_string(n_points) +
                           " material points, " +
                           std::to_string(particle_handler.n_global_particles()) +
                           " were read back."));
    ar >> time >> step >> time_step >> output_index >> max_point_speed >>
      removed_points >> removed_mass >> n_repartitions >> statistics_length >>
      output_writer >> names >> postprocessor_states;
    if (format >= 2)
      ar >> removed_energy;
    typename BoundaryConditions<dim>::ContactLocations contact;
    if (format >= 3)
      ar >> contact[0] >> contact[1];
    boundary_conditions.set_contact(contact);
    check_input(names == postprocessor_names,
                std::string("The checkpoint was written with the "
                           "postprocessors '" +
                           join(names) +
                           "'; 'Postprocess/List of postprocessors' must "
                           "name the same to resume it."));
    // The removed points are counted once, on rank 0.
    const bool is_root = Utilities::MPI::this_mpi_process(mpi_communicator) == 0;
    n_lost_points      = is_root ? removed_points : 0;
    lost_mass          = is_root ? removed_mass : 0;
    lost_energy        = is_root ? removed_energy : 0;
    for (unsigned int i = 0; i < postprocessors.size(); ++i)
      {
        std::istringstream p_in(postprocessor_states[i]);
        postprocessors[i]->load_state(p_in);
      }
  }


  template <int dim>
  void
  Simulator<dim>::write_checkpoint()
  {
    TimerOutput::Scope t(timer, "checkpoint");
    const auto        start = std::chrono::steady_clock::now();
    const std::size_t bytes =
      checkpointing.write(grid.triangulation, particle_handler, serialize_state());
    pcout << "Checkpoint at step " << step << ", t = " << time << " s: "
          << bytes / 1e6 << " MB in "
          << std::chrono::duration<double>(std::chrono::steady_clock::now() -
                                           start)
               .count()
          << " s\n";
  }


  template <int dim>
  void
  Simulator<dim>::repartition()
  {
    TimerOutput::Scope t(timer, "repartition");
    const types::particle_index n_before =
      particle_handler.n_global_particles();
    particle_handler.prepare_for_coarsening_and_refinement();
    grid.triangulation.repartition();
    particle_handler.unpack_after_coarsening_and_refinement();
    grid.setup_partition_data();
    setup_nodal_fields();
    ++n_repartitions;
    // No point may be lost on the way.
    AssertThrow(particle_handler.n_global_particles() == n_before,
                ExcMessage("Repartitioning changed the number of material "
                           "points from " + std::to_string(n_before) +
                           " to " +
                           std::to_string(
                             particle_handler.n_global_particles()) +
                           "."));
  }


  template <int dim>
  double
  Simulator<dim>::compute_time_step() const
  {
    double dt = time_stepping.fixed_time_step;
    if (time_stepping.adaptive)
      dt = std::min(time_stepping.maximum_time_step,
                    time_stepping.cfl_number * active_cell_size /
                      (materials.max_wave_speed() + max_point_speed));
    // Land on the end time exactly rather than overshoot it.
    if (time + dt > time_stepping.end_time * (1 - 1e-12))
      dt = time_stepping.end_time - time;
    return dt;
  }


  template <int dim>
  void
  Simulator<dim>::zero_nodal_fields()
  {
    nodal.zero([this](NodalVector &v) { weights->zero_touched_entries(v); });
  }


  template <int dim>
  void
  Simulator<dim>::compute_nodal_velocity(NodalVector &velocity_out)
  {
    TimerOutput::Scope t(timer, "nodal update");
    for (const unsigned int i : weights->active_dofs())
      {
        const double m = nodal.mass.local_element(i);
        velocity_out.local_element(i) =
          m > 0 ? nodal.momentum.local_element(i) / m : 0.;
      }
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
    const double       dt    = time_step;
    const double       alpha = time_stepping.local_damping;
    for (const unsigned int i : weights->active_dofs())
      {
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
      }
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
    for (const unsigned int i : weights->active_dofs())
      nodal.velocity_new.local_element(i) = brought_velocity(i);
    boundary_conditions.apply_friction(nodal.mass,
                                       nodal.velocity_new,
                                       nodal.acceleration,
                                       dt);
    for (const unsigned int i : weights->active_dofs())
      nodal.velocity_new.local_element(i) +=
        dt * nodal.acceleration.local_element(i);
    boundary_conditions.constrain_updated_velocity(nodal.velocity_new);
    // The acceleration consistent with the constrained velocity change
    // from u, so that the FLIP update of the points respects the
    // constraints too.
    for (const unsigned int i : weights->active_dofs())
      nodal.acceleration.local_element(i) =
        (nodal.velocity_new.local_element(i) - brought_velocity(i)) / dt;
  }


  template <int dim>
  void
  Simulator<dim>::set_max_point_speed(const double v_max2)
  {
    // A bad point makes the largest speed infinite on every rank: the
    // reduction that exists anyway tells all ranks to stop.
    max_point_speed = Utilities::MPI::max(
      point_update.first_bad_point().empty() ? std::sqrt(v_max2) :
                                std::numeric_limits<double>::infinity(),
      mpi_communicator);
    if (!std::isfinite(max_point_speed))
      stop_on_blow_up("a value became infinite or NaN.", true);
  }


  template <int dim>
  void
  Simulator<dim>::stop_on_blow_up(const std::string &reason,
                                  const bool         during_step)
  {
    using Layout = PropertyLayout<dim>;
    // Which point: the first bad one, or else the fastest.
    std::string here = point_update.first_bad_point();
    if (here.empty())
      {
        double fastest = -1;
        for (const auto &point : particle_handler)
          {
            const auto v =
              read_vector<dim>(&point.get_properties()[Layout::velocity]);
            if (v.norm() > fastest)
              {
                fastest = v.norm();
                std::ostringstream s;
                s << "the fastest material point, " << point.get_id()
                  << " at (" << point.get_location() << ") in cell "
                  << point.get_surrounding_cell()->id().to_string()
                  << ", moves at " << v.norm() << " m/s";
                here = s.str();
              }
          }
        const double global = Utilities::MPI::max(fastest, mpi_communicator);
        if (fastest < global)
          here.clear();
      }
    // The grid-to-particle check stops inside a step, the energy check
    // after it.
    std::ostringstream when_stream;
    if (during_step)
      when_stream << "in step " << step + 1 << " (from t = " << time
                  << " s to " << time + time_step << " s)";
    else
      when_stream << "by step " << step << " (t = " << time << " s)";
    const std::string when = when_stream.str();
    std::string       point_description;
    for (const auto &d : Utilities::MPI::all_gather(mpi_communicator, here))
      if (!d.empty())
        {
          point_description = d;
          break;
        }
    write_output(true);
    throw std::runtime_error(
      "The run became unstable " + when + ": " + reason + " First: " +
      point_description + ". The state at this step was written to " +
      output_writer.directory() +
      " (statistics, and the particle files if 'Output/Write particles' is "
      "on). " +
      StabilityMonitor<dim>::advice(time_step,
                                    materials.max_wave_speed(),
                                    active_cell_size,
                                    time_stepping.adaptive));
  }


  template <int dim>
  void
  Simulator<dim>::relocate_points()
  {
    TimerOutput::Scope t(timer, "locate points");
    const auto n_lost_before = n_lost_points;
    if (point_relocation.can_locate_while_moving())
      // Step 1 was done by update_points_from_grid().
      point_relocation.relocate_leavers(particle_handler);
    else
      point_relocation.relocate(particle_handler);
    const auto n_new_lost =
      Utilities::MPI::sum(n_lost_points - n_lost_before, mpi_communicator);
    if (n_new_lost > 0 && error_on_lost_points)
      {
        std::string first =
          lost_point_descriptions.empty() ? std::string("(on another rank)") :
                                            lost_point_descriptions.front();
        throw std::runtime_error(
          "At step " + std::to_string(step) + ", t = " + std::to_string(time) +
          " s, " + std::to_string(n_new_lost) +
          " material point(s) left the mesh; the first: " + first +
          ". Enlarge the mesh, constrain the boundary it crossed, or set "
          "'Material points/Points leaving the mesh = remove' to remove such "
          "points and report their mass.");
      }
    if (n_new_lost > 0)
      pcout << "Warning: " << n_new_lost << " material point(s) left the "
            << "mesh at t = " << time << " s and were removed.\n";
  }


  template <int dim>
  void
  Simulator<dim>::do_time_step()
  {
    zero_nodal_fields();
    prepare_transfer();
    time_step = compute_time_step();
    point_update.set_time_step(time_step);
    const UpdateScheme scheme = time_stepping.scheme;
    // Particle to grid (with the forces, unless USF updates the stress
    // first).
    weights->map_mass_and_momentum(scheme != UpdateScheme::usf);
    compute_nodal_velocity(nodal.velocity);
    if (scheme == UpdateScheme::usf)
      {
        weights->update_stress(nodal.velocity, false);
        weights->map_forces();
      }
    if (transfer.scheme().filters_brought_velocity())
      {
        TimerOutput::Scope t(timer, "transfer filter");
        transfer.scheme().filter_brought_velocity(*weights,
                                                  boundary_conditions,
                                                  nodal);
      }
    update_nodal_kinematics();
    // Grid to particle (MUSL: and the new momentum back to the nodes).
    set_max_point_speed(
      weights->update_points_from_grid(scheme == UpdateScheme::musl));
    if (scheme == UpdateScheme::usl)
      weights->update_stress(nodal.velocity_new, false);
    else if (scheme == UpdateScheme::musl)
      {
        compute_nodal_velocity(nodal.velocity_new);
        weights->update_stress(nodal.velocity_new,
                               transfer.apic() != nullptr);
      }
    time += time_step;
    ++step;
    relocate_points();
  }


  template <int dim>
  void
  Simulator<dim>::prepare_transfer()
  {
    active_cell_size =
      Utilities::MPI::min(weights->prepare(), mpi_communicator);
  }


  template <int dim>
  GlobalStatistics<dim>
  Simulator<dim>::compute_statistics() const
  {
    using Layout = PropertyLayout<dim>;
    GlobalStatistics<dim> s;
    s.time      = time;
    s.time_step = time_step;
    s.step      = step;
    for (const auto &point : particle_handler)
      {
        const auto           props = point.get_properties();
        const double         m     = props[Layout::mass];
        const Tensor<1, dim> v     = read_vector<dim>(&props[Layout::velocity]);
        s.mass += m;
        s.volume += props[Layout::volume];
        s.momentum += m * v;
        const auto energy = energy_of_point(props.data(), point.get_location());
        s.kinetic_energy += energy[0];
        s.strain_energy += energy[1];
        s.gravitational_potential_energy += energy[2];
        s.mean_speed += v.norm();
        s.max_speed = std::max(s.max_speed, v.norm());
        s.centre_of_mass += m * point.get_location();
      }
    s.n_points = particle_handler.n_global_particles();
    s.mass     = Utilities::MPI::sum(s.mass, mpi_communicator);
    s.volume   = Utilities::MPI::sum(s.volume, mpi_communicator);
    s.momentum = Utilities::MPI::sum(s.momentum, mpi_communicator);
    s.kinetic_energy = Utilities::MPI::sum(s.kinetic_energy, mpi_communicator);
    s.strain_energy  = Utilities::MPI::sum(s.strain_energy, mpi_communicator);
    s.gravitational_potential_energy =
      Utilities::MPI::sum(s.gravitational_potential_energy, mpi_communicator);
    s.removed_energy = Utilities::MPI::sum(lost_energy, mpi_communicator);
    s.mean_speed =
      Utilities::MPI::sum(s.mean_speed, mpi_communicator) /
      std::max<double>(1, s.n_points);
    s.max_speed      = Utilities::MPI::max(s.max_speed, mpi_communicator);
    s.centre_of_mass = Utilities::MPI::sum(s.centre_of_mass, mpi_communicator) /
                       (s.mass > 0 ? s.mass : 1);
    s.mean_velocity = s.momentum / (s.mass > 0 ? s.mass : 1);
    return s;
  }


  template <int dim>
  std::array<double, 3>
  Simulator<dim>::energy_of_point(const double *props, const Point<dim> &x) const
  {
    using Layout             = PropertyLayout<dim>;
    const double      m      = props[Layout::mass];
    const Material   &material =
      materials[static_cast<unsigned int>(props[Layout::material_id])];
    return {{0.5 * m * read_vector<dim>(&props[Layout::velocity]).norm_square(),
             props[Layout::volume] *
               material.model->strain_energy_density(
                 read_symmetric_tensor(&props[Layout::stress])),
             -m * (time_stepping.gravity * x)}};
  }


  template <int dim>
  std::pair<Tensor<1, 3>, double>
  Simulator<dim>::spin_angular_momentum(
    const Point<dim>     &centre,
    const Tensor<1, dim> &mean_velocity) const
  {
    using Layout     = PropertyLayout<dim>;
    const auto cross = [](const Tensor<1, dim> &a, const Tensor<1, dim> &b) {
      Tensor<1, 3> c;
      if constexpr (dim == 2)
        c[2] = a[0] * b[1] - a[1] * b[0];
      else
        c = cross_product_3d(a, b);
      return c;
    };
    const bool   affine = transfer.apic() != nullptr;
    Tensor<1, 3> L;
    double       scale = 0;
    for (const auto &point : particle_handler)
      {
        const auto           props = point.get_properties();
        const double         m     = props[Layout::mass];
        const Tensor<1, dim> r     = point.get_location() - centre;
        const Tensor<1, dim> v =
          read_vector<dim>(&props[Layout::velocity]) - mean_velocity;
        L += m * cross(r, v);
        // With the absolute velocity: not zero for a body in pure
        // translation, whose spin is zero.
        scale += m * r.norm() * (v + mean_velocity).norm();
        if (affine)
          L += m * Apic<dim>::affine_angular_momentum(
                     &props[transfer_slot]);
      }
    return {Utilities::MPI::sum(L, mpi_communicator),
            Utilities::MPI::sum(scale, mpi_communicator)};
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
                                  property_names(),
                                  time,
                                  output_index++,
                                  mpi_communicator);
    const auto s = compute_statistics();
    // Collective: every rank takes part, only rank 0 writes.
    const auto   removed_points = Utilities::MPI::sum(n_lost_points, mpi_communicator);
    const double removed_mass   = Utilities::MPI::sum(lost_mass, mpi_communicator);
    if (statistics_file.is_open())
      {
        statistics_file << std::setprecision(10) << s.time << ' ' << s.step
                        << ' ' << s.time_step << ' ' << s.n_points << ' '
                        << s.mass;
        for (unsigned int d = 0; d < dim; ++d)
          statistics_file << ' ' << s.momentum[d];
        statistics_file << ' ' << s.kinetic_energy << ' ' << s.strain_energy
                        << ' ' << s.gravitational_potential_energy << ' '
                        << s.mean_speed;
        for (unsigned int d = 0; d < dim; ++d)
          statistics_file << ' ' << s.centre_of_mass[d];
        statistics_file << ' ' << removed_points << ' ' << removed_mass
                        << '\n';
        statistics_file.flush();
      }
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
          p->initialize(*this);
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
    while (time < time_stepping.end_time * (1 - 1e-12))
      {
        do_time_step();
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
        const bool output_step =
          output_writer.output_due(time, time_step, time_stepping.end_time);
        for (auto &p : postprocessors)
          p->execute(*this, output_step);
        write_output(false);
        ++steps_this_run;
        if (time < time_stepping.end_time * (1 - 1e-12) &&
            checkpointing.due(steps_this_run, mpi_communicator))
          write_checkpoint();
        if (checkpointing.stop_requested(steps_this_run) &&
            time < time_stepping.end_time * (1 - 1e-12))
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
            time >= time_stepping.end_time * (1 - 1e-12))
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

    std::ostringstream report;
    report << "# dealii-mpm report: " << postprocessor_names.size()
           << " postprocessor(s)\n";
    for (const auto &warning : warnings)
      report << "# warning: " << warning << '\n';
    for (auto &p : postprocessors)
      p->write_report(*this, report);
    if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
      {
        std::ofstream(output_writer.directory() + "report.txt") << report.str();
        if (!postprocessors.empty())
          pcout << report.str();
      }
    const auto total_lost = Utilities::MPI::sum(n_lost_points, mpi_communicator);
    if (total_lost > 0)
      pcout << "Removed " << total_lost << " material point(s) that left the "
            << "mesh, mass " << Utilities::MPI::sum(lost_mass, mpi_communicator)
            << " kg.\n";
    const double wall = wall_seconds();
    pcout << "Done: " << step << " steps, "
          << particle_handler.n_global_particles() << " points, wall time "
          << wall << " s (steps " << wall - steps_start << " s), "
          << static_cast<double>(steps_this_run) *
               particle_handler.n_global_particles() / (wall - steps_start)
          << " particle-steps/s in the steps\n";
    if (Utilities::MPI::n_mpi_processes(mpi_communicator) > 1)
      pcout << "Load balance: " << n_repartitions
            << " repartition(s); busiest rank holds "
            << LoadBalancing<dim>::imbalance(particle_handler, mpi_communicator)
            << " x the mean number of points.\n";
    const auto &located = point_relocation.statistics();
    if (located.n_points_mapped > 0)
      pcout << "Point location (rank 0): "
            << 100. * located.n_points_moved / located.n_points_mapped
            << " % of the point-steps changed cell, "
            << located.n_points_sent << " point(s) sent to another rank; "
            << located.n_full_sorts
            << " step(s) needed deal.II's full sort; storage put back in "
               "cell order "
            << located.n_reorders << " time(s) (" << located.reorder_seconds
            << " s).\n";
    timer.print_summary();
  }


  template class Simulator<2>;
  template class Simulator<3>;
} // namespace MPM

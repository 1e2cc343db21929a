// The Simulator's checkpoints and restart (the state that is not in the
// mesh or the points) and the repartitioning of the mesh among ranks.

#include <deal.II/base/mpi.h>

#include <boost/archive/binary_iarchive.hpp>
#include <boost/archive/binary_oarchive.hpp>
#include <boost/serialization/array.hpp>
#include <boost/serialization/string.hpp>
#include <boost/serialization/utility.hpp>
#include <boost/serialization/vector.hpp>

#include <mpm/base/input_error.h>
#include <mpm/parallel/thread_chunks.h>
#include <mpm/solver/simulator.h>

#include <chrono>
#include <sstream>

namespace MPM
{
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
    const auto removed = lost_points.totals(mpi_communicator);
    const std::uint64_t n_points    = particle_handler.n_global_particles();
    const std::uint64_t n_cells     = grid.triangulation.n_global_active_cells();
    // 2: the removed points' energy appended; 3: the walls' contact state;
    // 4: the largest state-dependent wave speed; 5: the points' mass times
    // their shifts through periodic boundaries; 6: the rest criterion's
    // state; 7: the energies of the run's start for the stability check
    // 8: the normal forces the frictional walls remember; 9: those of the
    // second walls of 3D edge nodes (older formats are still read).
    const unsigned int      format        = 9;
    const Tensor<1, dim> wrapped_shift = wrapped_mass_shift();
    std::array<double, dim> wrapped_shift_values;
    for (unsigned int d = 0; d < dim; ++d)
      wrapped_shift_values[d] = wrapped_shift[d];
    const unsigned int  space_dim   = dim;
    std::uint64_t       stats_bytes = 0;
    stats_bytes = statistics_file.length();
    stats_bytes = Utilities::MPI::broadcast(mpi_communicator, stats_bytes, 0);

    std::vector<std::string> postprocessor_states;
    for (const auto &p : postprocessors)
      {
        std::ostringstream out;
        p->save_state(out);
        postprocessor_states.push_back(out.str());
      }

    const auto wall_states =
      WallNodeStates<dim>::gather(mpi_communicator,
                                  boundary_conditions.wall_node_states());
    const auto contact    = wall_states.contact_lists();
    const auto remembered = wall_states.remembered_lists();
    const auto remembered_edge = wall_states.remembered_edge_lists();

    std::ostringstream state;
    {
      boost::archive::binary_oarchive ar(state);
      ar << format << space_dim << n_points << n_cells << time << step
         << time_step << output_index << max_point_speed << removed.n_points
         << removed.mass << n_repartitions << stats_bytes << output_writer
         << postprocessor_names << postprocessor_states << removed.energy
         << contact[0] << contact[1] << max_state_wave_speed
         << wrapped_shift_values << rest_criterion << stability_monitor
         << remembered.first << remembered.second << remembered_edge.first
         << remembered_edge.second;
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
    check_input(format >= 1 && format <= 9 && space_dim == dim,
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
    std::array<std::vector<Point<dim>>, 2> contact;
    if (format >= 3)
      ar >> contact[0] >> contact[1];
    // Older checkpoints: the value the set-up computed from the points.
    if (format >= 4)
      ar >> max_state_wave_speed;
    std::array<double, dim> wrapped_shift_values{};
    if (format >= 5)
      ar >> wrapped_shift_values;
    if (format >= 6)
      ar >> rest_criterion;
    // Older checkpoints: the energies of the resumed state (set-up).
    if (format >= 7)
      ar >> stability_monitor;
    // Older checkpoints: no memory (N* = N at the next contact).
    std::vector<Point<dim>> remembered_locations;
    std::vector<double>     remembered_forces;
    if (format >= 8)
      ar >> remembered_locations >> remembered_forces;
    std::vector<Point<dim>> remembered_edge_locations;
    std::vector<double>     remembered_edge_forces;
    if (format >= 9)
      ar >> remembered_edge_locations >> remembered_edge_forces;
    boundary_conditions.set_wall_node_states(
      WallNodeStates<dim>::from_lists(contact,
                                      remembered_locations,
                                      remembered_forces,
                                      remembered_edge_locations,
                                      remembered_edge_forces));
    check_input(names == postprocessor_names,
                std::string("The checkpoint was written with the "
                           "postprocessors '" +
                           join(names) +
                           "'; 'Postprocess/List of postprocessors' must "
                           "name the same to resume it."));
    // The removed points are counted once, on rank 0.
    const bool is_root = Utilities::MPI::this_mpi_process(mpi_communicator) == 0;
    lost_points.restore({removed_points, removed_mass, removed_energy},
                        is_root);
    for (unsigned int d = 0; d < dim; ++d)
      wrapped_mass_shift_before_restart[d] =
        is_root ? wrapped_shift_values[d] : 0;
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
    const auto start = std::chrono::steady_clock::now();
    point_relocation.prepare_for_checkpoint(particle_handler);
    const std::size_t bytes = checkpointing.write(grid.triangulation,
                                                  particle_handler,
                                                  point_properties.names(),
                                                  serialize_state());
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
    const OneThreadScope one_thread;
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


  // The members defined here (the class itself is instantiated in
  // simulator.cc): one explicit instantiation per member, so that
  // the Simulator's files can share one translation unit (unity
  // build) without instantiating the class twice.
#define MPM_INSTANTIATE(dim)                                                   \
  template std::string Simulator<dim>::serialize_state() const;                \
  template void        Simulator<dim>::deserialize_state(const std::string &); \
  template void        Simulator<dim>::write_checkpoint();                     \
  template void        Simulator<dim>::repartition();

  MPM_INSTANTIATE(2)
  MPM_INSTANTIATE(3)
#undef MPM_INSTANTIATE
} // namespace MPM

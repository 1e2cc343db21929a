// The end of a run: the report of the postprocessors (report.txt) and the
// summary on the screen (wall time, throughput, memory, what the bounds and
// the point location did).

#include <deal.II/base/utilities.h>

#include <mpm/solver/simulator.h>

#include <fstream>
#include <sstream>

namespace MPM
{
  template <int dim>
  void
  Simulator<dim>::write_report() const
  {
    std::ostringstream report;
    report << "# dealii-mpm report: " << postprocessor_names.size()
           << " postprocessor(s)\n";
    for (const auto &warning : warnings)
      report << "# warning: " << warning << '\n';
    if (rest_criterion.at_rest())
      {
        const std::string stop =
          rest_criterion.description(time, time_stepping.end_time);
        report << "# " << stop << '\n';
        pcout << "The run " << stop << ".\n";
      }
    // Only in scenes with such a material: every other report is unchanged.
    if (materials.has_state_dependent_stiffness())
      report << "# state-dependent stiffness: " << step
             << " steps; largest P-wave speed of those points at the end "
             << max_state_wave_speed << " m/s\n";
    for (auto &p : postprocessors)
      p->write_report(report);
    if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
      {
        std::ofstream(output_writer.directory() + "report.txt") << report.str();
        if (!postprocessors.empty())
          pcout << report.str();
      }
  }


  template <int dim>
  void
  Simulator<dim>::print_run_summary(const double       wall,
                                    const double       steps_wall,
                                    const unsigned int steps_this_run) const
  {
    const auto removed = lost_points.totals(mpi_communicator);
    if (removed.n_points > 0)
      pcout << "Removed " << removed.n_points
            << " material point(s) that left the "
            << "mesh, mass " << removed.mass << " kg.\n";
    pcout << "Done: " << step << " steps, "
          << particle_handler.n_global_particles() << " points, wall time "
          << wall << " s (steps " << steps_wall << " s), "
          << static_cast<double>(steps_this_run) *
               particle_handler.n_global_particles() / steps_wall
          << " particle-steps/s in the steps\n";
    {
      // The peak resident set (the high-water mark of the whole run,
      // libraries included), summed over the ranks: what a run of this
      // size needs; the benchmark scripts take the memory per point from
      // the difference between two sizes.
      Utilities::System::MemoryStats memory;
      Utilities::System::get_memory_stats(memory);
      pcout << "Peak memory: "
            << Utilities::MPI::sum(static_cast<double>(memory.VmHWM),
                                   mpi_communicator) /
                 1024.
            << " MiB resident (all ranks)\n";
    }
    // How often a material's 'Minimum density' acted: a bound on the
    // physics, which the user should see.
    if (materials.has_volume_bound())
      pcout << "Minimum density: "
            << Utilities::MPI::sum(point_update.n_volume_bounded(),
                                   mpi_communicator)
            << " stress update(s) kept a point's volume at its material's "
               "bound (all ranks, this invocation).\n";
    if (Utilities::MPI::n_mpi_processes(mpi_communicator) > 1)
      pcout << "Load balance: " << n_repartitions
            << " repartition(s); busiest rank holds "
            << LoadBalancing<dim>::imbalance(particle_handler, mpi_communicator)
            << " x the mean number of points.\n";
    const auto &located = point_relocation.statistics();
    if (located.n_points_mapped > 0)
      pcout << "Point location (rank 0): "
            << 100. * located.n_points_moved / located.n_points_mapped
            << " % of the point-steps changed cell, " << located.n_points_sent
            << " point(s) sent to another rank; " << located.n_full_sorts
            << " step(s) needed deal.II's full sort; storage put back in "
               "cell order "
            << located.n_reorders << " time(s) (" << located.reorder_seconds
            << " s).\n";
    if (located.n_points_put_back > 0)
      pcout << "Walls (rank 0): " << located.n_points_put_back
            << " time(s) a point that had crossed a wall by a little was "
               "put back onto it; the farthest by "
            << located.largest_put_back << " m ("
            << located.largest_put_back_fraction
            << " of its cell; 'Wall overshoot tolerance').\n";
    if (!grid.periodic_boundaries.empty())
      pcout << "Periodic boundaries (rank 0): " << located.n_points_wrapped
            << " point move(s) through them.\n";
    timer.print_summary();
  }


  // The members defined here (the class itself is instantiated in
  // simulator.cc): one explicit instantiation per member, so that
  // the Simulator's files can share one translation unit (unity
  // build) without instantiating the class twice.
#define MPM_INSTANTIATE(dim)                                    \
  template void Simulator<dim>::write_report() const;           \
  template void Simulator<dim>::print_run_summary(const double, \
                                                  const double, \
                                                  const unsigned int) const;

  MPM_INSTANTIATE(2)
  MPM_INSTANTIATE(3)
#undef MPM_INSTANTIATE
} // namespace MPM

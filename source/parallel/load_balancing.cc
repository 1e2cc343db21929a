#include <deal.II/base/mpi.h>

#include <mpm/parallel/load_balancing.h>

namespace MPM
{
  template <int dim>
  void
  LoadBalancing<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Parallel");
    prm.declare_entry("Cell weight",
                      "1",
                      Patterns::Integer(1),
                      "Weight of every cell in the partition of the mesh "
                      "among MPI ranks (>= 1; the cost of a cell whether or "
                      "not it holds points: memory, ghost exchange).");
    prm.declare_entry("Point weight",
                      "10",
                      Patterns::Integer(0),
                      "Weight of each material point in its cell's weight "
                      "(the cost of a point in a step relative to 'Cell "
                      "weight').");
    prm.declare_entry("Check interval",
                      "100",
                      Patterns::Integer(0),
                      "Every this many steps the ranks compare their "
                      "numbers of points; 0 = never repartition after the "
                      "first partition by points.");
    prm.declare_entry("Imbalance threshold",
                      "1.2",
                      Patterns::Double(1),
                      "Repartition when the busiest rank holds more than "
                      "this many times the mean number of points.");
    prm.leave_subsection();
  }


  template <int dim>
  void
  LoadBalancing<dim>::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Parallel");
    cell_weight    = prm.get_integer("Cell weight");
    point_weight   = prm.get_integer("Point weight");
    check_interval = prm.get_integer("Check interval");
    threshold      = prm.get_double("Imbalance threshold");
    prm.leave_subsection();
  }


  template <int dim>
  void
  LoadBalancing<dim>::connect(
    parallel::distributed::Triangulation<dim> &triangulation,
    const Particles::ParticleHandler<dim>     &particle_handler)
  {
    triangulation.signals.weight.connect(
      [this, &particle_handler](
        const typename Triangulation<dim>::cell_iterator &cell,
        const typename Triangulation<dim>::CellStatus     status)
        -> unsigned int {
        // The mesh is never refined: every cell persists.
        (void)status;
        return cell_weight +
               point_weight * particle_handler.n_particles_in_cell(cell);
      });
  }


  template <int dim>
  double
  LoadBalancing<dim>::imbalance(
    const Particles::ParticleHandler<dim> &particle_handler,
    const MPI_Comm                         comm)
  {
    const double local = particle_handler.n_locally_owned_particles();
    const double max   = Utilities::MPI::max(local, comm);
    const double mean =
      Utilities::MPI::sum(local, comm) / Utilities::MPI::n_mpi_processes(comm);
    return mean > 0 ? max / mean : 1.;
  }


  template <int dim>
  bool
  LoadBalancing<dim>::repartition_due(
    const unsigned int                     step,
    const Particles::ParticleHandler<dim> &particle_handler,
    const MPI_Comm                         comm) const
  {
    if (Utilities::MPI::n_mpi_processes(comm) == 1 || check_interval == 0 ||
        step % check_interval != 0)
      return false;
    return imbalance(particle_handler, comm) > threshold;
  }


  template class LoadBalancing<2>;
  template class LoadBalancing<3>;
} // namespace MPM

#include <mpm/material_points/property_layout.h>
#include <mpm/solver/lost_points.h>

#include <sstream>
#include <stdexcept>

namespace MPM
{
  template <int dim>
  void
  LostPoints<dim>::declare_parameters(ParameterHandler &prm)
  {
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
  }


  template <int dim>
  void
  LostPoints<dim>::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Material points");
    error_on_lost = prm.get("Points leaving the mesh") == "error";
    prm.leave_subsection();
  }


  template <int dim>
  void
  LostPoints<dim>::connect(Particles::ParticleHandler<dim> &particle_handler,
                           const EnergyOfPoint             &energy_of_point)
  {
    particle_handler.signals.particle_lost.connect(
      [this, energy_of_point](
        const typename Particles::ParticleIterator<dim> &particle,
        const typename Triangulation<dim>::active_cell_iterator &) {
        const double *props = particle->get_properties().data();
        const double  m     = props[PropertyLayout<dim>::mass];
        ++n_points;
        mass += m;
        const auto e = energy_of_point(props, particle->get_location());
        energy += e[0] + e[1] + e[2];
        std::ostringstream s;
        s << "material point " << particle->get_id() << " (mass " << m
          << " kg) left the mesh at (" << particle->get_location() << ")";
        descriptions.push_back(s.str());
      });
  }


  template <int dim>
  void
  LostPoints<dim>::check(const types::particle_index n_before,
                         const unsigned int          step,
                         const double                time,
                         const MPI_Comm              comm,
                         const ConditionalOStream   &pcout) const
  {
    const auto n_new = Utilities::MPI::sum(n_points - n_before, comm);
    if (n_new > 0 && error_on_lost)
      {
        const std::string first = descriptions.empty() ?
                                    std::string("(on another rank)") :
                                    descriptions.front();
        throw std::runtime_error(
          "At step " + std::to_string(step) + ", t = " + std::to_string(time) +
          " s, " + std::to_string(n_new) +
          " material point(s) left the mesh; the first: " + first +
          ". Enlarge the mesh, constrain the boundary it crossed, or set "
          "'Material points/Points leaving the mesh = remove' to remove such "
          "points and report their mass.");
      }
    if (n_new > 0)
      pcout << "Warning: " << n_new << " material point(s) left the "
            << "mesh at t = " << time << " s and were removed.\n";
  }


  template <int dim>
  typename LostPoints<dim>::Totals
  LostPoints<dim>::totals(const MPI_Comm comm) const
  {
    Totals t;
    t.n_points = Utilities::MPI::sum(n_points, comm);
    const std::array<double, 2> local{{mass, energy}};
    std::array<double, 2>       global;
    Utilities::MPI::sum(ArrayView<const double>(local),
                        comm,
                        ArrayView<double>(global));
    t.mass   = global[0];
    t.energy = global[1];
    return t;
  }


  template <int dim>
  void
  LostPoints<dim>::restore(const Totals &totals, const bool is_root)
  {
    n_points = is_root ? totals.n_points : 0;
    mass     = is_root ? totals.mass : 0;
    energy   = is_root ? totals.energy : 0;
  }


  template class LostPoints<2>;
  template class LostPoints<3>;
} // namespace MPM

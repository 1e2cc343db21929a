#ifndef mpm_solver_lost_points_h
#define mpm_solver_lost_points_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <deal.II/particles/particle_handler.h>

#include <array>
#include <functional>
#include <string>
#include <vector>

namespace MPM
{
  using namespace dealii;

  /**
   * The ledger of the material points that left the mesh ('Material
   * points/Points leaving the mesh'): no point is lost silently.
   *
   * The ParticleHandler reports a point that left the domain through its
   * particle_lost signal (PointRelocation raises it as deal.II's sort
   * would). The ledger counts each such point, its mass and the energy it
   * takes away (the stability check compares the remaining points with
   * what remains available to them, GlobalStatistics::removed_energy), and
   * keeps a description of each for the message. After each relocation,
   * check() stops the run naming the first point ('error', the default) or
   * warns ('remove'). The totals go to the statistics file, the checkpoint
   * and the end-of-run report.
   */
  template <int dim>
  class LostPoints
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm);

    void
    parse_parameters(ParameterHandler &prm);

    /// A point's kinetic, strain and gravitational potential energy from
    /// its properties and position.
    using EnergyOfPoint =
      std::function<std::array<double, 3>(const double *, const Point<dim> &)>;

    /**
     * Count every point @p particle_handler reports lost, with the
     * energies @p energy_of_point gives it.
     */
    void
    connect(Particles::ParticleHandler<dim> &particle_handler,
            const EnergyOfPoint             &energy_of_point);

    /// The points lost on this rank so far: taken before a relocation,
    /// for check() after it.
    types::particle_index
    n_local() const
    {
      return n_points;
    }

    /**
     * After a relocation that started with n_local() = @p n_before: if
     * any rank lost points in it, stop the run at @p step and @p time
     * naming the first ('error') or warn through @p pcout ('remove').
     * Collective.
     */
    void
    check(const types::particle_index n_before,
          const unsigned int          step,
          const double                time,
          const MPI_Comm              comm,
          const ConditionalOStream   &pcout) const;

    /// The points removed, their mass and energy, over all ranks.
    struct Totals
    {
      types::particle_index n_points = 0;
      double                mass     = 0;
      double                energy   = 0;
    };

    /// Totals over the ranks. Collective.
    Totals
    totals(const MPI_Comm comm) const;

    /// The totals of a resumed run, counted once, on rank 0
    /// (@p is_root).
    void
    restore(const Totals &totals, const bool is_root);

  private:
    bool                     error_on_lost = true;
    types::particle_index    n_points      = 0;
    double                   mass          = 0;
    /// This rank's share of the energy the removed points carried.
    double                   energy        = 0;
    std::vector<std::string> descriptions;
  };
} // namespace MPM

#endif

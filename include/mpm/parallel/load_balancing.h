#ifndef mpm_parallel_load_balancing_h
#define mpm_parallel_load_balancing_h

#include <deal.II/base/parameter_handler.h>

#include <deal.II/distributed/tria.h>

#include <deal.II/particles/particle_handler.h>

namespace MPM
{
  using namespace dealii;

  /**
   * When and how the mesh is repartitioned among MPI ranks so that each
   * rank holds about the same work.
   *
   * p4est's first partition gives each rank the same number of cells, but a
   * step costs in proportion to the material points and the cells that hold
   * them (empty cells take no part in a step, see doc/algorithm.md): a
   * landslide that fills a tenth of its mesh would run on one rank while
   * the others wait. The weight of a cell is therefore
   * `Cell weight + Point weight * (points in the cell)`, and the mesh is
   * repartitioned after the points are created and then whenever the
   * points have moved so that the busiest rank holds more than `Imbalance
   * threshold` times the mean number of points (checked every `Check
   * interval` steps, so that the check's reduction is cheap).
   *
   * On one rank nothing happens: the same code path serves one rank or
   * many.
   */
  template <int dim>
  class LoadBalancing
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm);

    void
    parse_parameters(ParameterHandler &prm);

    /**
     * Weigh the cells of @p triangulation by the points of
     * @p particle_handler when it is repartitioned.
     */
    void
    connect(parallel::distributed::Triangulation<dim> &triangulation,
            const Particles::ParticleHandler<dim>     &particle_handler);

    /**
     * Whether the mesh should be repartitioned after step @p step: a
     * collective call (one reduction every 'Check interval' steps), false
     * on one rank.
     */
    bool
    repartition_due(const unsigned int                     step,
                    const Particles::ParticleHandler<dim> &particle_handler,
                    const MPI_Comm                         comm) const;

    /**
     * The busiest rank's number of points over the mean (1 = balanced); a
     * collective call.
     */
    static double
    imbalance(const Particles::ParticleHandler<dim> &particle_handler,
              const MPI_Comm                         comm);

  private:
    unsigned int cell_weight    = 1;
    unsigned int point_weight   = 10;
    unsigned int check_interval = 100;
    double       threshold      = 1.2;
  };
} // namespace MPM

#endif

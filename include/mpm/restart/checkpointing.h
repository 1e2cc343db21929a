#ifndef mpm_restart_checkpointing_h
#define mpm_restart_checkpointing_h

#include <deal.II/base/parameter_handler.h>

#include <deal.II/distributed/tria.h>

#include <deal.II/particles/particle_handler.h>

#include <string>

namespace MPM
{
  using namespace dealii;

  /**
   * Checkpoints of a run and resuming from them, so that neither a crash
   * nor a job's time limit costs the run.
   *
   * A checkpoint is a folder `checkpoint/` in the output directory holding
   * the mesh and the material points with all their properties (deal.II's
   * parallel::distributed::Triangulation::save() with the points attached
   * by ParticleHandler::prepare_for_serialization()), the simulator's state
   * (`state`: time, step, statistics so far, postprocessors' records) and
   * a `manifest` with the size and CRC-32 of every file.
   *
   * Writing never destroys the last good checkpoint: the new one is written
   * to `checkpoint.new/`, its manifest last, and only then renamed to
   * `checkpoint/` (the old one is first renamed to `checkpoint.old/` and
   * removed after). A crash while writing leaves `checkpoint/` intact; a
   * crash between the two renames leaves `checkpoint.old/`, which resuming
   * falls back to. Resuming checks every file against the manifest, so a
   * truncated or damaged checkpoint is an error naming the file, never a
   * run that continues from garbage.
   */
  template <int dim>
  class Checkpointing
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm);

    /**
     * Read the "Checkpointing" subsection; checkpoints go to
     * @p output_directory (with a trailing '/').
     */
    void
    parse_parameters(ParameterHandler &prm, const std::string &output_directory);

    /**
     * Whether this run continues from the checkpoint in the output
     * directory.
     */
    bool
    resume() const
    {
      return resume_run;
    }

    /**
     * Whether to write a checkpoint after @p steps_this_run steps of this
     * invocation: every 'Steps between checkpoints' steps, after 'Minutes
     * between checkpoints' of wall time (rank 0's clock decides for all
     * ranks), and at the stop requested by 'Stop after steps'. Collective.
     */
    bool
    due(const unsigned int steps_this_run, const MPI_Comm comm);

    /**
     * Whether this invocation stops after @p steps_this_run steps ('Stop
     * after steps', e.g. to fit a batch job's time limit).
     */
    bool
    stop_requested(const unsigned int steps_this_run) const
    {
      return stop_after_steps > 0 && steps_this_run >= stop_after_steps;
    }

    /**
     * Write a checkpoint of @p triangulation with the points of
     * @p particle_handler, the names of their property slots
     * @p point_slots (PointProperties::names()) and the simulator's
     * @p state (the same on every rank; rank 0 writes it). Collective.
     * Returns the size in bytes.
     */
    std::size_t
    write(const parallel::distributed::Triangulation<dim> &triangulation,
          Particles::ParticleHandler<dim>                 &particle_handler,
          const std::vector<std::string>                  &point_slots,
          const std::string                               &state) const;

    /**
     * Check the last checkpoint against its manifest and its points'
     * slots against @p point_slots (the parameters of the resumed run
     * lay out the points' properties, and the points cannot be read back
     * into another layout), load the mesh and the points into
     * @p triangulation (which must hold the coarse mesh only) and
     * @p particle_handler (initialized on it), and return the simulator's
     * state. Collective; throws an InputError naming the file if the
     * checkpoint is missing, truncated or damaged, or its points' slots
     * differ.
     */
    std::string
    read(parallel::distributed::Triangulation<dim> &triangulation,
         Particles::ParticleHandler<dim>           &particle_handler,
         const std::vector<std::string>            &point_slots) const;

  private:
    /**
     * The folder to resume from: `checkpoint/`, or `checkpoint.old/` if a
     * crash came between the renames; empty if there is none.
     */
    std::string
    folder_to_resume_from() const;

    std::string  directory;
    unsigned int step_interval    = 0;
    double       minutes_interval = 0;
    unsigned int stop_after_steps = 0;
    bool         resume_run       = false;
    double       last_checkpoint_wall_time = 0;
  };
} // namespace MPM

#endif

#ifndef mpm_solver_statistics_file_h
#define mpm_solver_statistics_file_h

#include <mpm/solver/statistics.h>

#include <cstdint>
#include <fstream>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace MPM
{
  /**
   * The file 'statistics' in the output directory: one row per output
   * time, one column (or dim columns) per quantity, named in its first
   * line. Header and rows come from one list of columns (columns()), so
   * that a new quantity is one line there. Written by rank 0 only.
   */
  template <int dim>
  class StatisticsFile
  {
  public:
    /// What a row shows: the global sums and the removed points.
    struct Row
    {
      const GlobalStatistics<dim> &statistics;
      types::particle_index        removed_points;
      double                       removed_mass;
      /// Added to the centre of mass: the mesh's local origin
      /// (BackgroundGrid::get_local_origin()), so that the file speaks
      /// map coordinates.
      Tensor<1, dim> local_origin;
    };

    /**
     * Open @p name: a new file with its header, or, resuming a run, the
     * file cut back to the @p resume_length bytes it had at the
     * checkpoint (the rows the stopped run wrote after it will be written
     * again) and appended to. @p with_pore_water: the water's columns
     * follow the others (a scene with a saturated material).
     */
    void
    open(const std::string  &name,
         const bool          resume,
         const std::uint64_t resume_length,
         const bool          with_pore_water);

    bool
    is_open() const
    {
      return file.is_open();
    }

    /// Bytes written so far (for a checkpoint; 0 where not open).
    std::uint64_t
    length() const;

    void
    write_row(const Row &row);

  private:
    struct Column
    {
      std::string name;
      /// Empty for a count.
      std::string  unit;
      unsigned int n_components;
      /// Writes the column's value(s), each preceded by a space.
      std::function<void(std::ostream &, const Row &)> write;
    };

    /// The columns, in their order in the file.
    std::vector<Column>
    columns() const;

    bool with_pore_water = false;

    /// Mutable: its write position is read by length().
    mutable std::ofstream file;
  };
} // namespace MPM

#endif

#include <deal.II/base/mpi.h>

#include <mpm/material_points/property_layout.h>
#include <mpm/postprocess/postprocessor.h>
#include <mpm/solver/simulator.h>

#include <algorithm>
#include <array>
#include <iomanip>
#include <limits>
#include <vector>

namespace MPM
{
  namespace Postprocessors
  {
    /**
     * The pore pressure and the effective stress of the saturated points
     * at the end of the run: the volume-weighted mean, the least and the
     * largest pore pressure, the 1st and 99th percentiles of the points'
     * pore pressures, and the mean effective vertical stress (the
     * last coordinate's normal stress, tension positive). A load shared
     * between the water and the skeleton (Skempton's B under undrained
     * loading, a drained end state) reads off these.
     */
    template <int dim>
    class PorePressure : public PostprocessorWithState<dim, PorePressure<dim>>
    {
    public:
      static void
      declare_parameters(ParameterHandler &)
      {}

      void
      execute(const bool) override
      {}

      void
      write_report(std::ostream &report) override
      {
        using Layout       = PropertyLayout<dim>;
        const auto &water  = this->get_pore_water();
        // sum V p, sum V, sum V sigma'_vv; least and largest p.
        std::array<double, 3> sums{};
        double least = std::numeric_limits<double>::max();
        double largest = -std::numeric_limits<double>::max();
        std::vector<double>   pressures;
        const auto           &grid = this->get_grid();
        if (water.active())
          for (const auto &point : this->get_particle_handler())
            {
              const auto props = point.get_properties();
              if (props[water.porosity_slot()] == 0)
                continue;
              const double V = props[Layout::volume];
              const double p = props[water.pressure_slot()];
              const auto   stress = grid.to_scene_frame(
                read_symmetric_tensor(&props[Layout::stress]));
              sums[0] += V * p;
              sums[1] += V;
              sums[2] += V * stress[dim - 1][dim - 1];
              least   = std::min(least, p);
              largest = std::max(largest, p);
              pressures.push_back(p);
            }
        const MPI_Comm comm = this->get_mpi_communicator();
        Utilities::MPI::sum(ArrayView<const double>(sums.data(), 3),
                            comm,
                            ArrayView<double>(sums.data(), 3));
        least   = Utilities::MPI::min(least, comm);
        largest = Utilities::MPI::max(largest, comm);
        // The 1st and 99th percentiles (nearest rank) of all ranks' points:
        // a pressure oscillation shows in them before the extremes.
        const std::vector<std::vector<double>> all_pressures =
          Utilities::MPI::gather(comm, pressures, 0);
        pressures.clear();
        for (const auto &rank_pressures : all_pressures)
          pressures.insert(pressures.end(),
                           rank_pressures.begin(),
                           rank_pressures.end());
        std::sort(pressures.begin(), pressures.end());
        // (Only rank 0 has them; the report is rank 0's.)
        const auto percentile = [&](const double q) {
          if (pressures.empty())
            return std::numeric_limits<double>::quiet_NaN();
          return pressures[static_cast<std::size_t>(
            q * static_cast<double>(pressures.size() - 1))];
        };
        report << "## pore pressure of the saturated points at the end\n";
        if (sums[1] == 0)
          {
            report << "no saturated point\n";
            return;
          }
        report << std::setprecision(8)
               << "mean pore pressure (Pa): " << sums[0] / sums[1] << '\n'
               << "least pore pressure (Pa): " << least << '\n'
               << "largest pore pressure (Pa): " << largest << '\n'
               << "1st / 99th percentile of the points' pore pressure (Pa): "
               << percentile(0.01) << " / " << percentile(0.99) << '\n'
               << "mean effective vertical stress (Pa): " << sums[2] / sums[1]
               << '\n'
               << std::setprecision(6);
      }

      template <class Archive>
      void
      serialize(Archive &, const unsigned int)
      {}
    };
  } // namespace Postprocessors
} // namespace MPM

MPM_REGISTER_POSTPROCESSOR(MPM::Postprocessors::PorePressure,
                           "pore pressure",
                           "the saturated points' pore pressure and effective "
                           "vertical stress at the end.")

#include <deal.II/base/mpi.h>

#include <mpm/material_points/property_layout.h>
#include <mpm/postprocess/postprocessor.h>
#include <mpm/solver/simulator.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iomanip>
#include <limits>
#include <vector>

namespace MPM
{
  namespace Postprocessors
  {
    /**
     * The collapse of a water column of width a and height 2 a (n^2 = 2)
     * against the surge front measured by Martin and Moyce (1952): the
     * front's distance from the back wall over a, Z, at the dimensionless
     * times T = t sqrt(2 g / a) of their table (../shared/REFERENCES.md).
     * The front is the largest x + V^(1/dim) / 2 of the points (the far
     * edge of the foremost point), measured from 'Back wall position';
     * the column starts at Z = 1. The report gives Z beside the measured
     * value at each tabulated T (the first step at or past it) and the
     * largest relative difference.
     */
    template <int dim>
    class DamBreak : public PostprocessorWithState<dim, DamBreak<dim>>
    {
    public:
      static void
      declare_parameters(ParameterHandler &prm)
      {
        prm.declare_entry("Column width",
                          "0.1",
                          Patterns::Double(0),
                          "a in m: the width of the column at the start "
                          "(its height 2 a).");
        prm.declare_entry("Back wall position",
                          "0",
                          Patterns::Double(),
                          "x in m of the wall the column leans on; the "
                          "front runs towards +x.");
      }

      void
      parse_parameters(ParameterHandler &prm) override
      {
        width     = prm.get_double("Column width");
        back_wall = prm.get_double("Back wall position");
      }

      void
      initialize() override
      {
        fronts.clear();
      }

      void
      execute(const bool) override
      {
        if (fronts.size() == reference.size())
          return;
        const double g = this->get_time_stepping().gravity.norm();
        const double T = this->get_time() * std::sqrt(2 * g / width);
        if (T < reference[fronts.size()][0])
          return;
        const auto &grid  = this->get_grid();
        double      front = -std::numeric_limits<double>::max();
        for (const auto &point : this->get_particle_handler())
          {
            const double x = grid.to_scene_frame(point.get_location())[0];
            const double V =
              point.get_properties()[PropertyLayout<dim>::volume];
            front = std::max(front, x + 0.5 * std::pow(V, 1. / dim));
          }
        front = Utilities::MPI::max(front, this->get_mpi_communicator());
        fronts.push_back({{T, (front - back_wall) / width}});
      }

      void
      write_report(std::ostream &report) override
      {
        report << "## dam break: surge front Z = x / a against Martin and "
                  "Moyce (1952), n^2 = 2, a = "
               << width << " m; T = t sqrt(2 g / a)\n";
        double largest = 0;
        for (unsigned int i = 0; i < fronts.size(); ++i)
          {
            const double Z_ref = reference[i][1];
            largest = std::max(largest,
                               std::abs(fronts[i][1] - Z_ref) / Z_ref);
            report << std::fixed << std::setprecision(3) << "Z at T = "
                   << reference[i][0] << ": " << fronts[i][1]
                   << " (measured " << Z_ref << ", step at T = "
                   << fronts[i][0] << ")\n";
          }
        report << "largest |Z - Z_measured| / Z_measured: "
               << std::setprecision(4) << largest << '\n'
               << std::defaultfloat << std::setprecision(6);
      }

      template <class Archive>
      void
      serialize(Archive &ar, const unsigned int)
      {
        ar &fronts;
      }

    private:
      double width     = 0.1;
      double back_wall = 0;
      /// (T, Z) the points reached at each tabulated T.
      std::vector<std::array<double, 2>> fronts;
      /// Martin and Moyce's (T, Z), n^2 = 2.
      static constexpr std::array<std::array<double, 2>, 8> reference{
        {{{0.832, 1.217}},
         {{1.219, 1.474}},
         {{1.997, 2.292}},
         {{2.547, 2.995}},
         {{3.345, 4.134}},
         {{4.034, 4.944}},
         {{5.091, 6.980}},
         {{6.306, 8.966}}}};
    };
  } // namespace Postprocessors
} // namespace MPM

MPM_REGISTER_POSTPROCESSOR(MPM::Postprocessors::DamBreak,
                           "dam break",
                           "a water column's surge front against Martin and "
                           "Moyce (1952).")

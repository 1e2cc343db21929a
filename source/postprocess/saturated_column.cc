#include <deal.II/base/mpi.h>

#include <mpm/material_points/property_layout.h>
#include <mpm/postprocess/postprocessor.h>
#include <mpm/solver/simulator.h>

#include <algorithm>
#include <cmath>
#include <iomanip>

namespace MPM
{
  namespace Postprocessors
  {
    /**
     * A saturated layer at rest under its own weight, its surface at y_s
     * (the last coordinate) and the water table at y_w <= y_s: hydrostatic
     * pore pressure p = rho_w |g| (y_w - y) and the effective vertical
     * stress sigma'_yy = -((rho_d + n rho_w) |g| (y_s - y) - p), the
     * buoyant weight below the water table (Terzaghi's principle). Started
     * in that state ('Initial pore pressure' and a geostatic 'Initial
     * stress'), nothing should move. The report gives, at the end, the
     * largest difference of the points' p and sigma'_yy from these over
     * their largest value, and the points' largest speed (skeleton and
     * water).
     */
    template <int dim>
    class SaturatedColumn
      : public PostprocessorWithState<dim, SaturatedColumn<dim>>
    {
    public:
      static void
      declare_parameters(ParameterHandler &prm)
      {
        prm.declare_entry("Surface elevation",
                          "1",
                          Patterns::Double(),
                          "y_s in m (z in 3D): the top of the layer.");
        prm.declare_entry("Water table elevation",
                          "1",
                          Patterns::Double(),
                          "y_w in m, at most y_s.");
      }

      void
      parse_parameters(ParameterHandler &prm) override
      {
        surface     = prm.get_double("Surface elevation");
        water_table = prm.get_double("Water table elevation");
      }

      void
      execute(const Simulator<dim> &, const bool) override
      {}

      void
      write_report(const Simulator<dim> &simulator,
                   std::ostream         &report) override
      {
        using Layout         = PropertyLayout<dim>;
        const auto  &water   = simulator.get_pore_water();
        const auto  &mats    = simulator.get_materials();
        const double g       = simulator.get_time_stepping().gravity.norm();
        const double rho_w   = water.density();
        // Largest |error| of p and sigma'_yy, their largest exact values,
        // largest squared speeds of skeleton and water.
        std::array<double, 6> m{};
        for (const auto &point : simulator.get_particle_handler())
          {
            const auto props = point.get_properties();
            const double n   = props[water.porosity_slot()];
            if (n == 0)
              continue;
            const auto &material =
              mats[static_cast<unsigned int>(props[Layout::material_id])];
            const double y =
              simulator.get_grid().to_scene_frame(point.get_location())[dim -
                                                                        1];
            const double p_exact = rho_w * g * (water_table - y);
            const double s_exact =
              -((material.density + material.porosity * rho_w) * g *
                  (surface - y) -
                p_exact);
            const auto stress =
              simulator.get_grid().to_scene_frame(
                read_symmetric_tensor(&props[Layout::stress]));
            m[0] = std::max(m[0],
                            std::abs(props[water.pressure_slot()] - p_exact));
            m[1] = std::max(m[1], std::abs(p_exact));
            m[2] = std::max(m[2],
                            std::abs(stress[dim - 1][dim - 1] - s_exact));
            m[3] = std::max(m[3], std::abs(s_exact));
            m[4] = std::max(
              m[4], read_vector<dim>(&props[Layout::velocity]).norm_square());
            m[5] =
              std::max(m[5],
                       read_vector<dim>(&props[water.velocity_slot()])
                         .norm_square());
          }
        Utilities::MPI::max(ArrayView<const double>(m.data(), 6),
                            simulator.get_mpi_communicator(),
                            ArrayView<double>(m.data(), 6));
        report << "Saturated layer at rest (surface " << surface
               << " m, water table " << water_table << " m):\n"
               << std::scientific << std::setprecision(3)
               << "  pore pressure: max |p - rho_w g (y_w - y)| / max p = "
               << m[0] / m[1] << " (max p " << m[1] << " Pa)\n"
               << "  effective stress: max |s'_yy - exact| / max |s'_yy| = "
               << m[2] / m[3] << " (max " << m[3] << " Pa)\n"
               << "  largest speed: skeleton " << std::sqrt(m[4])
               << " m/s, water " << std::sqrt(m[5]) << " m/s\n"
               << std::defaultfloat << std::setprecision(6);
      }

      template <class Archive>
      void
      serialize(Archive &, const unsigned int)
      {}

    private:
      double surface     = 1;
      double water_table = 1;
    };
  } // namespace Postprocessors
} // namespace MPM

MPM_REGISTER_POSTPROCESSOR(MPM::Postprocessors::SaturatedColumn,
                           "saturated column",
                           "a saturated layer at rest: hydrostatic pore "
                           "pressure and buoyant effective stress.")

#include <deal.II/base/mpi.h>

#include <mpm/base/input_error.h>
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
     * A saturated layer under its own weight, its surface at y_s (the last
     * coordinate), its base at y_b, the water table at y_w (below the
     * surface, or above it: the layer submerged), and in steady vertical
     * seepage if its base is held at an excess pore pressure Delta above
     * the hydrostatic one (an artesian base, the top drained): pore
     * pressure
     *
     *   p = rho_w |g| (y_w - y) + Delta (y_s - y) / (y_s - y_b),
     *
     * and the effective vertical stress sigma'_yy = -(sigma_v - p) with
     * sigma_v = (rho_d + n rho_w) |g| (y_s - y) + rho_w |g| max(0, y_w -
     * y_s) the weight above (Terzaghi's principle): the buoyant weight,
     * less the seepage force. With Delta = 0 nothing should move. With
     * Delta > 0 the water flows up at Darcy's flux q = (k / mu) Delta /
     * (y_s - y_b) relative to the skeleton (failure, sigma' = 0, at Delta
     * = (rho_sat - rho_w) |g| (y_s - y_b)). The report gives, at the end,
     * the largest difference of the points' p and sigma'_yy from these
     * over their largest value, the points' largest speed (skeleton and
     * water) and, with Delta > 0, their mean flux n (v_w - v_s) against q.
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
                          "y_w in m; above y_s: the layer is submerged.");
        prm.declare_entry("Base elevation",
                          "0",
                          Patterns::Double(),
                          "y_b in m: the layer's base (steady seepage "
                          "only).");
        prm.declare_entry("Base excess pore pressure",
                          "0",
                          Patterns::Double(),
                          "Delta in Pa: the pore pressure above the "
                          "hydrostatic one at the base, in steady seepage "
                          "up to the drained top; 0: at rest.");
      }

      void
      parse_parameters(ParameterHandler &prm) override
      {
        surface     = prm.get_double("Surface elevation");
        water_table = prm.get_double("Water table elevation");
        base        = prm.get_double("Base elevation");
        excess      = prm.get_double("Base excess pore pressure");
        check_input(excess == 0 || base < surface,
                    "Postprocess/saturated column/Base elevation (" +
                      prm.get("Base elevation") +
                      ") must lie below the Surface elevation (" +
                      prm.get("Surface elevation") + ").");
      }

      void
      execute(const bool) override
      {}

      void
      write_report(std::ostream &report) override
      {
        using Layout         = PropertyLayout<dim>;
        const auto  &water   = this->get_pore_water();
        const auto  &mats    = this->get_materials();
        const double g       = this->get_time_stepping().gravity.norm();
        const double rho_w   = water.density();
        // Largest |error| of p and sigma'_yy, their largest exact values,
        // largest squared speeds of skeleton and water.
        std::array<double, 6> m{};
        // Seepage: sums of V, V n (v_w - v_s)_y and V k / mu.
        std::array<double, 3> flux{};
        const auto           &grid = this->get_grid();
        for (const auto &point : this->get_particle_handler())
          {
            const auto props = point.get_properties();
            const double n   = props[water.porosity_slot()];
            if (n == 0)
              continue;
            const auto &material =
              mats[static_cast<unsigned int>(props[Layout::material_id])];
            const double y = grid.to_scene_frame(point.get_location())[dim - 1];
            const double p_exact =
              rho_w * g * (water_table - y) +
              (excess == 0 ? 0. : excess * (surface - y) / (surface - base));
            // Submerged ('Pore water/Submerged'), the points hold the
            // excess over the still water's pressure, whose surface is
            // the water table.
            const double p_points = water.is_submerged() ?
                                      p_exact - rho_w * g * (water_table - y) :
                                      p_exact;
            const double s_exact =
              -((material.density + material.porosity * rho_w) * g *
                  (surface - y) +
                rho_w * g * std::max(0., water_table - surface) - p_exact);
            if (excess != 0)
              {
                const double V = props[Layout::volume];
                const auto   relative = this->get_grid().to_scene_frame(
                  read_vector<dim>(&props[water.velocity_slot()]) -
                  read_vector<dim>(&props[Layout::velocity]));
                flux[0] += V;
                flux[1] += V * n * relative[dim - 1];
                flux[2] += V * material.permeability /
                           water.get_viscosity();
              }
            const auto stress = this->get_grid().to_scene_frame(
              read_symmetric_tensor(&props[Layout::stress]));
            m[0] =
              std::max(m[0], std::abs(props[water.pressure_slot()] - p_points));
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
                            this->get_mpi_communicator(),
                            ArrayView<double>(m.data(), 6));
        Utilities::MPI::sum(ArrayView<const double>(flux.data(), 3),
                            this->get_mpi_communicator(),
                            ArrayView<double>(flux.data(), 3));
        if (excess == 0)
          report << "Saturated layer at rest (surface " << surface
                 << " m, water table " << water_table << " m):\n";
        else
          report << "Saturated layer in steady upward seepage (surface "
                 << surface << " m, base " << base << " m, water table "
                 << water_table << " m, excess pore pressure at the base "
                 << excess << " Pa):\n";
        report << std::scientific << std::setprecision(3)
               << (water.is_submerged() ?
                     "  excess pore pressure (submerged): max |p_e - exact| "
                     "/ max p = " :
                   excess == 0 ?
                     "  pore pressure: max |p - rho_w g (y_w - y)| / max p = " :
                     "  pore pressure: max |p - exact| / max p = ")
               << m[0] / m[1] << " (max p " << m[1] << " Pa)\n"
               << "  effective stress: max |s'_yy - exact| / max |s'_yy| = "
               << m[2] / m[3] << " (max " << m[3] << " Pa)\n"
               << "  largest speed: skeleton " << std::sqrt(m[4])
               << " m/s, water " << std::sqrt(m[5]) << " m/s\n";
        if (excess != 0)
          {
            // Darcy: q = (k / mu) Delta / H with the points' mean k / mu.
            const double q = flux[2] / flux[0] * excess / (surface - base);
            report << "  mean flux n (v_w - v_s)_y = " << flux[1] / flux[0]
                   << " m/s, Darcy's (k / mu) Delta / H = " << q
                   << " m/s, difference / q = "
                   << (flux[1] / flux[0] - q) / q << "\n";
          }
        report << std::defaultfloat << std::setprecision(6);
      }

      template <class Archive>
      void
      serialize(Archive &, const unsigned int)
      {}

    private:
      double surface     = 1;
      double water_table = 1;
      double base        = 0;
      double excess      = 0;
    };
  } // namespace Postprocessors
} // namespace MPM

MPM_REGISTER_POSTPROCESSOR(MPM::Postprocessors::SaturatedColumn,
                           "saturated column",
                           "a saturated layer at rest (hydrostatic pore "
                           "pressure, buoyant effective stress) or in "
                           "steady upward seepage (Darcy's flux).")

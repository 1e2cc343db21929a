#include <deal.II/base/mpi.h>

#include <mpm/base/input_error.h>
#include <mpm/material_points/property_layout.h>
#include <mpm/postprocess/postprocessor.h>
#include <mpm/solver/simulator.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace MPM
{
  namespace Postprocessors
  {
    /**
     * Simple shear of a hypoelastic layer by the whole MPM step: a layer
     * between a fixed base at y = y_b and a top moving at v_x = gamma_dot
     * H, periodic in x ('Mesh/Periodic boundaries'), started with the
     * velocity of steady shear, v_x = gamma_dot (y - y_b). The exact
     * motion is homogeneous, gamma = gamma_dot t, and with the Jaumann rate
     * (the default 'Materials/Objective stress rate') the exact stress of
     * an isotropic linear elastic layer is Dienes' (1979):
     * sigma_xy = G sin(gamma), sigma_xx = -sigma_yy = G (1 - cos(gamma)),
     * and with 'none' sigma_xy = G gamma, sigma_xx = sigma_yy = 0. The
     * report compares the volume-weighted mean stress of the points with
     * that at output times, the largest deviation over the run (divided by
     * G), the largest deviation of a single point at the end, and the
     * points' velocity against gamma_dot (y - y_b) (divided by the top's
     * speed): what the material-point driver checks for one point
     * (tests/material_point_simple_shear_*.prm), here through the grid,
     * the boundary conditions and moving points.
     */
    template <int dim>
    class SimpleShear : public PostprocessorWithState<dim, SimpleShear<dim>>
    {
    public:
      static void
      declare_parameters(ParameterHandler &prm)
      {
        prm.declare_entry("Shear rate",
                          "0.1",
                          Patterns::Double(),
                          "gamma_dot in 1/s (the top's speed divided by "
                          "the layer's height).");
        prm.declare_entry("Shear modulus",
                          "1e6",
                          Patterns::Double(0),
                          "G of the layer in Pa.");
        prm.declare_entry("Base elevation", "0", Patterns::Double(), "y_b in m.");
        prm.declare_entry("Layer height", "1", Patterns::Double(0), "H in m.");
        prm.declare_entry("Objective stress rate",
                          "jaumann",
                          Patterns::Selection("jaumann|none"),
                          "The closed form to compare with: that of the "
                          "Jaumann rate or of none (fixed axes); the same "
                          "as 'Materials/Objective stress rate'.");
      }

      void
      parse_parameters(ParameterHandler &prm) override
      {
        rate    = prm.get_double("Shear rate");
        modulus = prm.get_double("Shear modulus");
        base    = prm.get_double("Base elevation");
        height  = prm.get_double("Layer height");
        jaumann = prm.get("Objective stress rate") == "jaumann";
      }

      void
      execute(const Simulator<dim> &simulator, const bool output_step) override
      {
        const auto   mean  = mean_stress(simulator);
        const double gamma = rate * simulator.get_time();
        const auto   exact = exact_stress(gamma);
        double       error = 0;
        for (unsigned int k = 0; k < 3; ++k)
          error = std::max(error, std::abs(mean[k] - exact[k]) / modulus);
        max_mean_error = std::max(max_mean_error, error);
        if (output_step)
          {
            std::ostringstream line;
            line << std::setprecision(6) << std::setw(8) << gamma;
            for (unsigned int k = 0; k < 3; ++k)
              line << std::setw(14) << mean[k] / modulus << std::setw(14)
                   << exact[k] / modulus;
            line << std::setw(14) << error << '\n';
            table += line.str();
          }
      }

      void
      write_report(const Simulator<dim> &simulator, std::ostream &report) override
      {
        using Layout       = PropertyLayout<dim>;
        const double gamma = rate * simulator.get_time();
        const auto   exact = exact_stress(gamma);
        const auto  &grid  = simulator.get_grid();
        // Largest deviations of single points at the end: stress / G and
        // velocity / (gamma_dot H).
        std::array<double, 2> worst{{0., 0.}};
        for (const auto &point : simulator.get_particle_handler())
          {
            const auto props = point.get_properties();
            const auto sigma = grid.to_scene_frame(
              read_symmetric_tensor(&props[Layout::stress]));
            const std::array<double, 3> s{{sigma[0][1], sigma[0][0], sigma[1][1]}};
            for (unsigned int k = 0; k < 3; ++k)
              worst[0] =
                std::max(worst[0], std::abs(s[k] - exact[k]) / modulus);
            const Point<dim> x = grid.to_scene_frame(point.get_location());
            // A vector turns back like a position (R^T v).
            const Tensor<1, dim> v = grid.to_scene_frame(
              Point<dim>(read_vector<dim>(&props[Layout::velocity])));
            Tensor<1, dim> v_exact;
            v_exact[0] = rate * (x[1] - base);
            worst[1]   = std::max(worst[1],
                                (v - v_exact).norm() /
                                  std::max(1e-300, std::abs(rate) * height));
          }
        const MPI_Comm comm = simulator.get_mpi_communicator();
        for (auto &w : worst)
          w = Utilities::MPI::max(w, comm);
        report << "## simple shear: volume-mean stress / G against the closed "
                  "form ("
               << (jaumann ? "Jaumann: sigma_xy = G sin(gamma), sigma_xx = "
                             "-sigma_yy = G (1 - cos(gamma))" :
                             "fixed axes: sigma_xy = G gamma")
               << ")\n"
               << "#  gamma    sxy/G mpm    sxy/G exact    sxx/G mpm    "
                  "sxx/G exact    syy/G mpm    syy/G exact   max error\n"
               << table
               << "max over the run of |mean stress - exact| / G: "
               << max_mean_error << "\nat gamma = " << gamma
               << ", largest |point stress - exact| / G: " << worst[0]
               << "\nat gamma = " << gamma
               << ", largest |point velocity - gamma_dot (y - y_b)| / "
                  "(gamma_dot H): "
               << worst[1] << '\n';
      }

      /// The state accumulated over the run (checkpoints).
      template <class Archive>
      void
      serialize(Archive &ar, const unsigned int)
      {
        ar & max_mean_error & table;
      }

    private:
      /// (sigma_xy, sigma_xx, sigma_yy) of Dienes' closed form.
      std::array<double, 3>
      exact_stress(const double gamma) const
      {
        if (!jaumann)
          return {{modulus * gamma, 0., 0.}};
        return {{modulus * std::sin(gamma),
                 modulus * (1 - std::cos(gamma)),
                 -modulus * (1 - std::cos(gamma))}};
      }

      /// Volume-weighted mean (sigma_xy, sigma_xx, sigma_yy), scene frame.
      static std::array<double, 3>
      mean_stress(const Simulator<dim> &simulator)
      {
        using Layout = PropertyLayout<dim>;
        std::vector<double> sums(4, 0.);
        for (const auto &point : simulator.get_particle_handler())
          {
            const auto   props  = point.get_properties();
            const double volume = props[Layout::volume];
            const auto   sigma  = simulator.get_grid().to_scene_frame(
              read_symmetric_tensor(&props[Layout::stress]));
            sums[0] += volume * sigma[0][1];
            sums[1] += volume * sigma[0][0];
            sums[2] += volume * sigma[1][1];
            sums[3] += volume;
          }
        Utilities::MPI::sum(sums, simulator.get_mpi_communicator(), sums);
        const double v = std::max(sums[3], 1e-300);
        return {{sums[0] / v, sums[1] / v, sums[2] / v}};
      }

      double      rate = 0.1, modulus = 1e6, base = 0, height = 1;
      bool        jaumann        = true;
      double      max_mean_error = 0;
      std::string table;
    };
  } // namespace Postprocessors
} // namespace MPM

MPM_REGISTER_POSTPROCESSOR(MPM::Postprocessors::SimpleShear,
                           "simple shear",
                           "a periodic layer sheared between a fixed base and a moving top against Dienes' closed form.")

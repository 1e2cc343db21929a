#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <mpm/base/input_error.h>
#include <mpm/material_points/property_layout.h>
#include <mpm/postprocess/postprocessor.h>
#include <mpm/solver/simulator.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iomanip>
#include <limits>
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
     *
     * With 'Closed form = false' the layer is not expected to stay elastic
     * (a softening layer in which a shear band forms,
     * prm/shear_band_softening.prm): the report lists the mean stress
     * against gamma (the shear stress the layer carries, a stress-strain
     * curve through the band) and, at the end, the profile across the
     * layer of the first state variable (the plastic shear strain of a
     * frictional model) in bins of 'Profile bin' and the band's
     * equivalent width, the integral of that profile over its largest
     * value.
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
        prm.declare_entry("Closed form",
                          "true",
                          Patterns::Bool(),
                          "Whether the layer is linear elastic and the "
                          "report compares it with the closed form; false "
                          "for a layer that yields (a shear band): the "
                          "report then lists its mean stress and the "
                          "profile of its plastic shear strain.");
        prm.declare_entry(
          "Averaging window",
          "",
          Patterns::Anything(),
          "'x_min, x_max' (m): the mean stress is taken over the points "
          "whose current x lies in this window; empty: over all points. "
          "For a layer of finite width with free ends, whose stress is "
          "homogeneous only away from the ends (a window a layer height or "
          "more from each end).");
        prm.declare_entry("Profile bin",
                          "0.05",
                          Patterns::Double(0),
                          "Height in m of the bins of the plastic shear "
                          "strain profile (Closed form = false).");
      }

      void
      parse_parameters(ParameterHandler &prm) override
      {
        rate    = prm.get_double("Shear rate");
        modulus = prm.get_double("Shear modulus");
        base    = prm.get_double("Base elevation");
        height  = prm.get_double("Layer height");
        jaumann = prm.get("Objective stress rate") == "jaumann";
        closed_form = prm.get_bool("Closed form");
        bin         = prm.get_double("Profile bin");
        const std::string window_text = prm.get("Averaging window");
        if (!window_text.empty())
          {
            const auto bounds = Utilities::split_string_list(window_text);
            check_input(bounds.size() == 2,
                        "Postprocess/simple shear/Averaging window = '" +
                          window_text + "': give 'x_min, x_max' or leave it "
                          "empty.");
            const std::string where =
              "Postprocess/simple shear/Averaging window = '" + window_text +
              "': ";
            window = {
              {parse_number(bounds[0], where), parse_number(bounds[1], where)}};
            check_input(window[0] < window[1],
                        "Postprocess/simple shear/Averaging window = '" +
                          window_text + "': x_min must be below x_max.");
          }
        if (!closed_form)
          check_input(bin > 0 && bin <= height,
                      "Postprocess/simple shear/Profile bin = " +
                        std::to_string(bin) +
                        ": must lie in (0, Layer height].");
      }

      void
      execute(const bool output_step) override
      {
        const auto   mean  = mean_stress();
        const double gamma = rate * this->get_time();
        if (!closed_form)
          {
            if (output_step)
              {
                std::ostringstream line;
                line << std::setprecision(6) << std::setw(8) << gamma;
                for (unsigned int k = 0; k < 3; ++k)
                  line << std::setw(14) << mean[k];
                line << '\n';
                table += line.str();
              }
            return;
          }
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
      write_report(std::ostream &report) override
      {
        using Layout       = PropertyLayout<dim>;
        const double gamma = rate * this->get_time();
        if (!closed_form)
          {
            write_band_report(gamma, report);
            return;
          }
        const auto   exact = exact_stress(gamma);
        const auto  &grid  = this->get_grid();
        // Largest deviations of single points (in the averaging window) at
        // the end: stress / G and
        // velocity / (gamma_dot H).
        std::array<double, 2> worst{{0., 0.}};
        for (const auto &point : this->get_particle_handler())
          {
            if (!in_window(grid, point.get_location()))
              continue;
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
        const MPI_Comm comm = this->get_mpi_communicator();
        for (auto &w : worst)
          w = Utilities::MPI::max(w, comm);
        report << "## simple shear: volume-mean stress / G against the closed "
                  "form ("
               << (jaumann ? "Jaumann: sigma_xy = G sin(gamma), sigma_xx = "
                             "-sigma_yy = G (1 - cos(gamma))" :
                             "fixed axes: sigma_xy = G gamma")
               << ")"
               << (std::isinf(window[0]) ?
                     std::string() :
                     ", points with x in [" + std::to_string(window[0]) +
                       ", " + std::to_string(window[1]) + "] m")
               << "\n"
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
      /**
       * The report of a yielding layer: its mean stress against gamma, the
       * profile of the first state variable across it (volume-weighted
       * bin means) and the equivalent width of that profile.
       */
      void
      write_band_report(const double gamma, std::ostream &report) const
      {
        using Layout = PropertyLayout<dim>;
        const unsigned int n_bins =
          static_cast<unsigned int>(std::ceil(height / bin - 1e-9));
        // Per bin: sum of V kappa, sum of V.
        std::vector<double> sums(2 * n_bins, 0.);
        const auto         &grid = this->get_grid();
        if (this->get_materials().max_n_state_variables() > 0)
          for (const auto &point : this->get_particle_handler())
            {
              const auto       props = point.get_properties();
              const Point<dim> x = grid.to_scene_frame(point.get_location());
              const double     s = (x[1] - base) / bin;
              if (!(s >= 0 && s < n_bins))
                continue;
              const unsigned int b = static_cast<unsigned int>(s);
              sums[2 * b] += props[Layout::volume] * props[Layout::state];
              sums[2 * b + 1] += props[Layout::volume];
            }
        Utilities::MPI::sum(sums, this->get_mpi_communicator(), sums);
        std::vector<double> profile(n_bins, 0.);
        double              largest = 0, integral = 0;
        for (unsigned int b = 0; b < n_bins; ++b)
          {
            if (sums[2 * b + 1] > 0)
              profile[b] = sums[2 * b] / sums[2 * b + 1];
            largest = std::max(largest, profile[b]);
            integral += profile[b] * bin;
          }
        report << "## simple shear of a yielding layer: volume-mean stress "
                  "(Pa) against gamma = top displacement / H\n"
               << "#  gamma       sigma_xy      sigma_xx      sigma_yy\n"
               << table << "## at gamma = " << gamma
               << ": first state variable (plastic shear strain) across "
                  "the layer, volume-weighted means in bins of "
               << bin << " m\n# y centre (m)  value\n";
        for (unsigned int b = 0; b < n_bins; ++b)
          report << std::setw(10) << base + (b + 0.5) * bin << std::setw(14)
                 << profile[b] << '\n';
        report << "largest bin value: " << largest
               << "\nequivalent band width (integral / largest, m): "
               << (largest > 0 ? integral / largest : 0.) << '\n';
      }

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

      /// Volume-weighted mean (sigma_xy, sigma_xx, sigma_yy), scene frame,
      /// over the points in the averaging window.
      std::array<double, 3>
      mean_stress() const
      {
        using Layout = PropertyLayout<dim>;
        std::vector<double> sums(4, 0.);
        const auto         &grid = this->get_grid();
        for (const auto &point : this->get_particle_handler())
          {
            if (!in_window(grid, point.get_location()))
              continue;
            const auto   props  = point.get_properties();
            const double volume = props[Layout::volume];
            const auto   sigma  = grid.to_scene_frame(
              read_symmetric_tensor(&props[Layout::stress]));
            sums[0] += volume * sigma[0][1];
            sums[1] += volume * sigma[0][0];
            sums[2] += volume * sigma[1][1];
            sums[3] += volume;
          }
        Utilities::MPI::sum(sums, this->get_mpi_communicator(), sums);
        const double v = std::max(sums[3], 1e-300);
        return {{sums[0] / v, sums[1] / v, sums[2] / v}};
      }

      /// Whether a point (mesh frame of @p grid) lies in the averaging
      /// window.
      bool
      in_window(const BackgroundGrid<dim> &grid, const Point<dim> &x) const
      {
        if (window[0] == -std::numeric_limits<double>::infinity() &&
            window[1] == std::numeric_limits<double>::infinity())
          return true;
        const double x_scene = grid.to_scene_frame(x)[0];
        return x_scene >= window[0] && x_scene <= window[1];
      }

      std::array<double, 2> window{{-std::numeric_limits<double>::infinity(),
                                    std::numeric_limits<double>::infinity()}};
      double      rate = 0.1, modulus = 1e6, base = 0, height = 1;
      bool        jaumann        = true;
      bool        closed_form    = true;
      double      bin            = 0.05;
      double      max_mean_error = 0;
      std::string table;
    };
  } // namespace Postprocessors
} // namespace MPM

MPM_REGISTER_POSTPROCESSOR(MPM::Postprocessors::SimpleShear,
                           "simple shear",
                           "a periodic layer sheared between a fixed base and a moving top against Dienes' closed form.")

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
     * An elastic column of initial height H0 on a base at y = y_b, laterally
     * confined (uniaxial strain) and loaded by its own weight, settled with
     * local damping. Equilibrium alone gives the Cauchy stress at a material
     * point of reference height Y: sigma_yy = -rho0 g (H0 - Y), the weight
     * of the material above over an area that uniaxial strain keeps, for
     * any constitutive law and any strain. The code's elastic model
     * integrates the rate of deformation, so in uniaxial strain it is
     * Hencky's: sigma_yy = M ln(lambda), M the P-wave modulus, lambda the
     * vertical stretch. Hence lambda(Y) = exp(-a (H0 - Y)) with a = rho0 g /
     * M, the current height y(Y) = (exp(a Y) - 1) exp(-a H0) / a, its
     * inverse Y(y) = ln(1 + a y exp(a H0)) / a, and the settled column
     * height H = (1 - exp(-a H0)) / a. The report compares sigma_yy of the
     * points with the exact value at their current height, over the base
     * layer (y - y_b < base layer thickness) and over the whole column
     * (relative L2 error), and the column height given by the points'
     * volumes (sum V / width, width = sum m / (rho0 H0)) with H. For a
     * stiff column (a H0 small) this is sigma_yy = -rho g (H0 - y); with a
     * soft one (a H0 = 0.5: 21 % settlement) points cross cells, the
     * large-deformation convergence case of Charlton, Coombs and Augarde
     * (2017).
     */
    template <int dim>
    class SelfWeightColumn : public Postprocessor<dim>
    {
    public:
      static void
      declare_parameters(ParameterHandler &prm)
      {
        prm.declare_entry("Column height", "1", Patterns::Double(0), "Initial height H0 in m (before the column settles).");
        prm.declare_entry("Base elevation", "0", Patterns::Double(), "y_b in m.");
        prm.declare_entry("Base layer thickness",
                          "0.1",
                          Patterns::Double(0),
                          "Points below y_b + this (m) form the base layer.");
      }

      void
      parse_parameters(ParameterHandler &prm) override
      {
        height     = prm.get_double("Column height");
        base       = prm.get_double("Base elevation");
        base_layer = prm.get_double("Base layer thickness");
      }

      void
      execute(const bool) override
      {}

      void
      write_report(std::ostream &report) override
      {
        using Layout   = PropertyLayout<dim>;
        const double g = this->get_time_stepping().gravity[dim - 1];
        // Volume-weighted sums per horizontal layer of thickness
        // base_layer: [volume, sigma_yy, exact], the L2 sums, and the
        // column's mass and volume.
        const unsigned int  n_layers = std::ceil(height / base_layer - 1e-9);
        std::vector<double> sums(3 * n_layers + 4, 0.);
        double              rho_ref = 0, modulus = 0;
        const auto         &materials = this->get_materials();
        for (const auto &point : this->get_particle_handler())
          {
            const auto      props = point.get_properties();
            const Material &material =
              materials[static_cast<unsigned int>(props[Layout::material_id])];
            rho_ref = material.density;
            modulus = material.model->p_wave_modulus();
          }
        const MPI_Comm comm = this->get_mpi_communicator();
        rho_ref             = Utilities::MPI::max(rho_ref, comm);
        modulus             = Utilities::MPI::max(modulus, comm);
        // a = rho0 g / M (g < 0 here: a is the compressive sense's
        // magnitude).
        const double a = rho_ref * std::abs(g) / modulus;
        const auto   reference_height = [&](const double y) {
          return a * height < 1e-12 ?
                   y :
                   std::log1p(a * y * std::exp(a * height)) / a;
        };
        for (const auto &point : this->get_particle_handler())
          {
            const auto   props  = point.get_properties();
            const double y      = point.get_location()[dim - 1] - base;
            const double exact  = rho_ref * g * (height - reference_height(y));
            const double sigma  = props[Layout::stress + dim - 1];
            const double volume = props[Layout::volume];
            sums[0] += volume * (sigma - exact) * (sigma - exact);
            sums[1] += volume * exact * exact;
            sums[2] += props[Layout::mass];
            sums[3] += volume;
            const unsigned int layer = std::min<unsigned int>(
              n_layers - 1, std::max(0., y / base_layer));
            sums[4 + 3 * layer] += volume;
            sums[5 + 3 * layer] += volume * sigma;
            sums[6 + 3 * layer] += volume * exact;
          }
        Utilities::MPI::sum(sums, comm, sums);
        const double scale = std::abs(rho_ref * g * height);
        report << "## self-weight column: sigma_yy against the exact "
                  "finite-strain solution, averaged over layers of "
               << base_layer << " m\n"
               << "# layer  mean sigma_yy mpm (Pa)  mean exact (Pa)  error / "
                  "(rho g H0)\n";
        for (unsigned int l = 0; l < n_layers; ++l)
          {
            const double v = sums[4 + 3 * l];
            if (v == 0)
              continue;
            const double mean = sums[5 + 3 * l] / v, mean_e = sums[6 + 3 * l] / v;
            report << std::setw(5) << l << std::setw(16) << mean
                   << std::setw(16) << mean_e << std::setw(16)
                   << (mean - mean_e) / scale << '\n';
          }
        const double base_mean   = sums[5] / sums[4];
        const double base_exact  = sums[6] / sums[4];
        const double width       = sums[2] / (rho_ref * height);
        const double column      = sums[3] / width;
        const double exact_column =
          a * height < 1e-12 ? height : -std::expm1(-a * height) / a;
        report << "base layer relative error |mpm - exact| / (rho g H0): "
               << std::abs(base_mean - base_exact) / scale
               << "\nwhole column relative L2 error: "
               << std::sqrt(sums[0] / sums[1])
               << "\nrho0 g H0 / M: " << a * height
               << "\ncolumn height from point volumes (m): " << column
               << "  exact: " << exact_column
               << "  error / settlement: "
               << (column - exact_column) /
                    std::max(1e-300, height - exact_column)
               << '\n';
      }

      /// Compares the state at the end of the run only: nothing to keep.
      void
      save_state(std::ostream &) const override
      {}

      void
      load_state(std::istream &) override
      {}

    private:
      double height = 1, base = 0, base_layer = 0.1;
    };
  } // namespace Postprocessors
} // namespace MPM

MPM_REGISTER_POSTPROCESSOR(MPM::Postprocessors::SelfWeightColumn,
                           "self-weight column",
                           "the column compressed by its own weight against its exact solution.")

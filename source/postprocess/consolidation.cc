#include <deal.II/base/mpi.h>

#include <mpm/base/input_error.h>
#include <mpm/material_points/property_layout.h>
#include <mpm/postprocess/postprocessor.h>
#include <mpm/solver/simulator.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

namespace MPM
{
  namespace Postprocessors
  {
    /**
     * Terzaghi's one-dimensional consolidation: a saturated layer of
     * thickness H, drained at its top (elevation z_t: y in 2D, z in 3D),
     * impermeable at its base, whose excess pore pressure u starts
     * uniform, u0, under a load that stays. Its series solution
     * (Terzaghi 1943; Verruijt, Soil Mechanics, ch. 15) is
     *
     *   u(Z, T) = u0 sum_m (2 / M) sin(M Z) exp(-M^2 T),  M = pi (2m+1) / 2,
     *
     * with Z = (z_t - z) / H the depth over the drainage length (with a
     * drained base 2 H below the top too, the distance to the nearer
     * drained face over H) and
     * T = c_v t / H^2 the time factor; the degree of consolidation is
     * U(T) = 1 - sum_m (2 / M^2) exp(-M^2 T) (U = 0.5 at T = 0.197, 0.9 at
     * T = 0.848). For a linear elastic skeleton of P-wave (oedometric)
     * modulus M_s, intrinsic permeability k and water of viscosity mu and
     * bulk modulus K_w, c_v = (k / mu) / (1 / M_s + n / K_w).
     *
     * At each of the 'Time factors' the report compares the points' excess
     * pore pressure (p minus the hydrostatic rho_w |g| (z_t - z)) with
     * u(Z, T) at the step's time: the largest and the root-mean-square
     * difference over u0, and U = 1 - sum V u / (u0 sum V) with U(T). It
     * also gives the time factors at which the points' U reaches 0.5 and
     * 0.9 (linear between steps).
     */
    template <int dim>
    class Consolidation
      : public PostprocessorWithState<dim, Consolidation<dim>>
    {
    public:
      static void
      declare_parameters(ParameterHandler &prm)
      {
        prm.declare_entry("Drained surface elevation",
                          "1",
                          Patterns::Double(),
                          "z_t in m (y in 2D, z in 3D): the layer's drained "
                          "top at the start.");
        prm.declare_entry("Layer thickness",
                          "1",
                          Patterns::Double(0),
                          "H in m: the drainage length, down to the "
                          "impermeable base (Drainage = top), or half the "
                          "layer (Drainage = top and base).");
        prm.declare_entry("Drainage",
                          "top",
                          Patterns::Selection("top|top and base"),
                          "Where the layer drains: at its top only, or at "
                          "its top and its base (2 H below the top; the "
                          "base a 'Drainage = drained' wall).");
        prm.declare_entry("Initial excess pore pressure",
                          "1e4",
                          Patterns::Double(0),
                          "u0 in Pa, the load the water carries at the "
                          "start.");
        prm.declare_entry("Coefficient of consolidation",
                          "0",
                          Patterns::Double(0),
                          "c_v in m^2/s; 0: from the scene's saturated "
                          "material (it must have one, linear elastic), "
                          "(k / mu) / (1 / M + n / K_w).");
        prm.declare_entry("Time factors",
                          "0.05, 0.1, 0.2, 0.5, 1",
                          Patterns::List(Patterns::Double(0)),
                          "T = c_v t / H^2 at which the isochrones are "
                          "compared.");
      }

      void
      parse_parameters(ParameterHandler &prm) override
      {
        top       = prm.get_double("Drained surface elevation");
        thickness = prm.get_double("Layer thickness");
        both_ends = prm.get("Drainage") == "top and base";
        u0        = prm.get_double("Initial excess pore pressure");
        c_v       = prm.get_double("Coefficient of consolidation");
        check_input(thickness > 0 && u0 > 0,
                    "Postprocess/consolidation: Layer thickness and Initial "
                    "excess pore pressure must be > 0.");
        time_factors.clear();
        for (const auto &t :
             Utilities::split_string_list(prm.get("Time factors")))
          time_factors.push_back(Utilities::string_to_double(t));
        std::sort(time_factors.begin(), time_factors.end());
      }

      void
      initialize() override
      {
        const auto &water = this->get_pore_water();
        check_input(water.active(),
                    "Postprocess/consolidation needs a saturated material "
                    "(Materials/NAME/Porosity > 0).");
        if (c_v == 0)
          {
            const auto &materials = this->get_materials();
            for (unsigned int m = 0; m < materials.size(); ++m)
              if (materials[m].porosity > 0)
                {
                  const double M = materials[m].model->p_wave_modulus();
                  c_v = materials[m].permeability / water.get_viscosity() /
                        (1 / M + materials[m].porosity /
                                   water.get_bulk_modulus());
                  break;
                }
          }
        rows.clear();
        crossing.assign(2, -1.);
        last_T = 0;
        last_U = 0;
      }

      void
      execute(const bool) override
      {
        const double T = c_v * this->get_time() / (thickness * thickness);
        const bool   at_factor =
          rows.size() < time_factors.size() && T >= time_factors[rows.size()];
        const bool watching = crossing[1] < 0;
        if (!at_factor && !watching)
          return;
        const auto   sums       = compare(T, at_factor);
        const double U = 1 - sums[0] / (u0 * sums[1]);
        const double targets[2] = {0.5, 0.9};
        for (unsigned int i = 0; i < 2; ++i)
          if (crossing[i] < 0 && U >= targets[i])
            crossing[i] =
              U > last_U ? last_T + (targets[i] - last_U) / (U - last_U) *
                                      (T - last_T) :
                           T;
        last_T = T;
        last_U = U;
        if (at_factor)
          rows.push_back({{T,
                           sums[2] / u0,
                           std::sqrt(sums[3] / sums[4]) / u0,
                           U,
                           degree_exact(T)}});
      }

      void
      write_report(std::ostream &report) override
      {
        // One 'label: value' a line (scripts/convergence.py reads them).
        report << "## consolidation: Terzaghi, H = " << thickness
               << " m, u0 = " << u0 << " Pa, c_v = " << std::setprecision(6)
               << c_v << " m^2/s; u = p - rho_w |g| (z_t - z), u_T the "
                  "series at the step's T\n";
        for (const auto &r : rows)
          {
            const std::string at = "at T = " + format_factor(r[0]);
            report << std::scientific << std::setprecision(3)
                   << "max |u - u_T| / u0 " << at << ": " << r[1] << '\n'
                   << "rms (u - u_T) / u0 " << at << ": " << r[2] << '\n'
                   << std::fixed << std::setprecision(4) << "U " << at
                   << ": " << r[3] << " (series " << r[4] << ")\n"
                   << std::defaultfloat;
          }
        report << std::setprecision(4) << "T at U = 0.5: " << crossing[0]
               << " (series 0.1967)\nT at U = 0.9: " << crossing[1]
               << " (series 0.8481)\n"
               << std::setprecision(6);
      }

      template <class Archive>
      void
      serialize(Archive &ar, const unsigned int)
      {
        ar &c_v &rows &crossing &last_T &last_U;
      }

    private:
      /// The time factor of a row as the parameter gave it (the step's T
      /// is a little past it).
      std::string
      format_factor(const double T) const
      {
        double closest = time_factors.empty() ? T : time_factors[0];
        for (const double t : time_factors)
          if (std::abs(t - T) < std::abs(closest - T))
            closest = t;
        std::ostringstream s;
        s << closest;
        return s.str();
      }

      /// u(Z, T) of the series (enough terms for 1e-12 at T >= 1e-4).
      double
      excess_exact(const double Z, const double T) const
      {
        double u = 0;
        for (unsigned int m = 0; m < 2000; ++m)
          {
            const double M    = numbers::PI * (2 * m + 1) / 2;
            const double term = 2 / M * std::sin(M * Z) * std::exp(-M * M * T);
            u += term;
            if (M * M * T > 40)
              break;
          }
        return u0 * u;
      }

      static double
      degree_exact(const double T)
      {
        double s = 0;
        for (unsigned int m = 0; m < 20000; ++m)
          {
            const double M = numbers::PI * (2 * m + 1) / 2;
            s += 2 / (M * M) * std::exp(-M * M * T);
            if (M * M * T > 40 && m > 10)
              break;
          }
        return 1 - s;
      }

      /// Over all saturated points: sum V u, sum V, max |u - u_T|,
      /// sum V (u - u_T)^2, sum V (the last three only if @p full: a row
      /// is due).
      std::array<double, 5>
      compare(const double T, const bool full) const
      {
        using Layout        = PropertyLayout<dim>;
        const auto  &water  = this->get_pore_water();
        const double gamma_w =
          water.density() * this->get_time_stepping().gravity.norm();
        const auto           &grid = this->get_grid();
        std::array<double, 5> sums{};
        for (const auto &point : this->get_particle_handler())
          {
            const auto props = point.get_properties();
            if (props[water.porosity_slot()] == 0)
              continue;
            const double z = grid.to_scene_frame(point.get_location())[dim - 1];
            const double V = props[Layout::volume];
            const double u =
              props[water.pressure_slot()] - gamma_w * (top - z);
            sums[0] += V * u;
            sums[1] += V;
            if (full)
              {
                const double depth =
                  both_ends ? std::min(top - z, z - (top - 2 * thickness)) :
                              top - z;
                const double Z = std::clamp(depth / thickness, 0., 1.);
                const double d = u - excess_exact(Z, T);
                sums[2]        = std::max(sums[2], std::abs(d));
                sums[3] += V * d * d;
                sums[4] += V;
              }
          }
        const MPI_Comm comm = this->get_mpi_communicator();
        const double   max  = Utilities::MPI::max(sums[2], comm);
        Utilities::MPI::sum(ArrayView<const double>(sums.data(), 5),
                            comm,
                            ArrayView<double>(sums.data(), 5));
        sums[2] = max;
        return sums;
      }

      double              top       = 1;
      double              thickness = 1;
      bool                both_ends = false;
      double              u0        = 1e4;
      double              c_v       = 0;
      std::vector<double> time_factors;
      /// Per time factor reached: T, max and rms error over u0, U, U(T).
      std::vector<std::array<double, 5>> rows;
      /// The time factors at which U reached 0.5 and 0.9 (-1: not yet).
      std::vector<double> crossing{-1., -1.};
      double              last_T = 0, last_U = 0;
    };
  } // namespace Postprocessors
} // namespace MPM

MPM_REGISTER_POSTPROCESSOR(MPM::Postprocessors::Consolidation,
                           "consolidation",
                           "Terzaghi's one-dimensional consolidation against "
                           "its series solution.")

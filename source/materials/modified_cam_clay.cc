#include <mpm/base/input_error.h>
#include <mpm/materials/modified_cam_clay.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace MPM
{
  namespace MaterialModels
  {
    namespace
    {
      /**
       * Relative tolerance of the return: the yield function against
       * p_c^2 and the flow rule's residual against kappa / v (the
       * volumetric strain that changes p by a factor e). Newton converges
       * quadratically, so this costs one iteration more than 1e-8 would,
       * and leaves the closed forms of the element tests to rounding.
       */
      constexpr double tolerance = 1e-11;

      /// Newton iterations of one return before the step is sub-stepped.
      constexpr unsigned int max_iterations = 50;

      /**
       * A sub-step changes the elastic trial pressure by at most a factor
       * exp(0.25) and the trial q by at most 0.25 times the pressure:
       * within that, Newton from the trial state converges in a few
       * iterations. MPM steps are far smaller (the CFL condition); the
       * material-point driver's too.
       */
      constexpr double max_substep_size = 0.25;

      /// Beyond this many sub-steps an update gives up.
      constexpr unsigned int max_substeps = 4096;

      std::string
      cam_clay_parameter(const std::string &entry)
      {
        return "modified cam clay/" + entry;
      }

      std::string
      number(const double x)
      {
        std::ostringstream s;
        s << x;
        return s.str();
      }

      double
      von_mises(const SymmetricTensor<2, 3> &s)
      {
        return std::sqrt(1.5 * scalar_product(s, s));
      }
    } // namespace


    void
    ModifiedCamClay::declare_parameters(ParameterHandler &prm)
    {
      prm.declare_entry("Slope of critical state line",
                        "1.0",
                        Patterns::Double(),
                        "M, the ratio q / p at the critical state; > 0. In "
                        "triaxial compression M = 6 sin(phi) / (3 - "
                        "sin(phi)).");
      prm.declare_entry("Lambda",
                        "0.2",
                        Patterns::Double(),
                        "lambda, the slope of the normal compression line "
                        "in v - ln(p) (v = 1 + e); > Kappa.");
      prm.declare_entry("Kappa",
                        "0.05",
                        Patterns::Double(),
                        "kappa, the slope of the swelling lines in "
                        "v - ln(p); > 0. The bulk modulus is v p / kappa.");
      prm.declare_entry("Initial void ratio",
                        "1.0",
                        Patterns::Double(),
                        "e0, the void ratio of every point at the start "
                        "(specific volume v0 = 1 + e0); > 0.");
      prm.declare_entry(
        "Initial preconsolidation pressure",
        "100e3",
        Patterns::Double(),
        "p_c0 in Pa, the size of the initial yield surface (where it "
        "crosses the p axis), the same for every point; > 0. A point whose "
        "initial stress lies outside that surface is taken as normally "
        "consolidated: p_c is raised to put its stress on the surface.");
      prm.declare_entry("Shear stiffness",
                        "constant Poisson's ratio",
                        Patterns::Selection("constant Poisson's ratio|"
                                            "constant shear modulus"),
                        "The elastic shear modulus: G = 3 (1 - 2 nu) / "
                        "(2 (1 + nu)) K, proportional to the pressure, or "
                        "'Shear modulus'.");
      prm.declare_entry("Poisson's ratio",
                        "0.3",
                        Patterns::Double(),
                        "nu, in (-1, 0.5); used for G with 'constant "
                        "Poisson's ratio', and for the default K0 = nu / "
                        "(1 - nu) in either case.");
      prm.declare_entry("Shear modulus",
                        "1e6",
                        Patterns::Double(),
                        "G in Pa, > 0, for 'constant shear modulus'.");
      prm.declare_entry(
        "Minimum pressure",
        "1e3",
        Patterns::Double(),
        "p_min in Pa, > 0: below it the bulk modulus is held at "
        "v p_min / kappa, so that a point at zero stress is not without "
        "stiffness (and the time step stays finite). Well below the "
        "pressures of interest.");
    }


    void
    ModifiedCamClay::parse_parameters(ParameterHandler &prm)
    {
      M                  = prm.get_double("Slope of critical state line");
      lambda             = prm.get_double("Lambda");
      kappa              = prm.get_double("Kappa");
      initial_void_ratio = prm.get_double("Initial void ratio");
      initial_preconsolidation_pressure =
        prm.get_double("Initial preconsolidation pressure");
      constant_shear_modulus =
        prm.get("Shear stiffness") == "constant shear modulus";
      poisson_ratio    = prm.get_double("Poisson's ratio");
      constant_G       = prm.get_double("Shear modulus");
      minimum_pressure = prm.get_double("Minimum pressure");

      check_input(M > 0,
                  cam_clay_parameter("Slope of critical state line") + " = " +
                    number(M) + ": must be > 0.");
      check_input(kappa > 0,
                  cam_clay_parameter("Kappa") + " = " + number(kappa) +
                    ": must be > 0.");
      check_input(lambda > kappa,
                  cam_clay_parameter("Lambda") + " = " + number(lambda) +
                    ": must be larger than Kappa = " + number(kappa) +
                    " (lambda - kappa is the plastic part of the "
                    "compression; the hardening divides by it).");
      check_input(initial_void_ratio > 0,
                  cam_clay_parameter("Initial void ratio") + " = " +
                    number(initial_void_ratio) + ": must be > 0.");
      check_input(initial_preconsolidation_pressure > 0,
                  cam_clay_parameter("Initial preconsolidation pressure") +
                    " = " + number(initial_preconsolidation_pressure) +
                    " Pa: must be > 0.");
      check_input(poisson_ratio > -1 && poisson_ratio < 0.5,
                  cam_clay_parameter("Poisson's ratio") + " = " +
                    number(poisson_ratio) + ": must lie in (-1, 0.5).");
      check_input(!constant_shear_modulus || constant_G > 0,
                  cam_clay_parameter("Shear modulus") + " = " +
                    number(constant_G) + " Pa: must be > 0.");
      check_input(minimum_pressure > 0,
                  cam_clay_parameter("Minimum pressure") + " = " +
                    number(minimum_pressure) + " Pa: must be > 0.");
    }


    double
    ModifiedCamClay::bulk_modulus(const double p, const double v) const
    {
      return v * std::max(p, minimum_pressure) / kappa;
    }


    double
    ModifiedCamClay::shear_modulus(const double K) const
    {
      return constant_shear_modulus ?
               constant_G :
               1.5 * (1 - 2 * poisson_ratio) / (1 + poisson_ratio) * K;
    }


    double
    ModifiedCamClay::elastic_pressure(const double p_n,
                                      const double d,
                                      const double v) const
    {
      const double c     = v / kappa;
      const double p_min = minimum_pressure;
      if (p_n >= p_min)
        {
          const double p = p_n * std::exp(c * d);
          if (p >= p_min)
            return p;
          // Exponential down to p_min, linear (K = c p_min) below.
          return p_min + c * p_min * (d - std::log(p_min / p_n) / c);
        }
      const double p = p_n + c * p_min * d;
      if (p <= p_min)
        return p;
      return p_min * std::exp(c * (d - (p_min - p_n) / (c * p_min)));
    }


    void
    ModifiedCamClay::update_stress(
      const SymmetricTensor<2, 3> &strain_increment,
      SymmetricTensor<2, 3>       &stress,
      const ArrayView<double>     &state,
      const double                 time_step) const
    {
      (void)time_step;
      AssertIndexRange(plastic_volumetric_strain, state.size());

      // Sub-steps a priori: the elastic trial's log pressure change and its
      // q change relative to the pressure.
      const double v   = state[specific_volume];
      const double p_n = -trace(stress) / 3.;
      const double p_ref =
        std::max({p_n, state[preconsolidation_pressure], minimum_pressure});
      const double                G = shear_modulus(bulk_modulus(p_n, v));
      const SymmetricTensor<2, 3> e = deviator(strain_increment);
      const double                size =
        std::max(std::abs(trace(strain_increment)) * v / kappa,
                 3 * G * std::sqrt(2. / 3. * scalar_product(e, e)) / p_ref) /
        max_substep_size;
      unsigned int n_sub =
        size < 1 ? 1u :
                   static_cast<unsigned int>(
                     std::min<double>(std::ceil(size), max_substeps));

      for (;;)
        {
          if (update_in_substeps(strain_increment, stress, state, n_sub))
            return;
          if (n_sub >= max_substeps)
            break;
          n_sub = std::min(4 * n_sub, max_substeps);
        }

      std::ostringstream message;
      message << std::setprecision(10)
              << "modified cam clay: the return mapping did not converge in "
              << max_iterations << " Newton iterations even with "
              << max_substeps << " sub-steps. Point state: stress (xx yy zz "
              << "xy yz xz) = " << stress[0][0] << ' ' << stress[1][1] << ' '
              << stress[2][2] << ' ' << stress[0][1] << ' ' << stress[1][2]
              << ' ' << stress[0][2] << " Pa, p_c = "
              << state[preconsolidation_pressure]
              << " Pa, v = " << state[specific_volume]
              << "; strain increment (xx yy zz xy yz xz) = "
              << strain_increment[0][0] << ' ' << strain_increment[1][1]
              << ' ' << strain_increment[2][2] << ' '
              << strain_increment[0][1] << ' ' << strain_increment[1][2]
              << ' ' << strain_increment[0][2] << '.';
      throw std::runtime_error(message.str());
    }


    bool
    ModifiedCamClay::update_in_substeps(
      const SymmetricTensor<2, 3> &strain_increment,
      SymmetricTensor<2, 3>       &stress,
      const ArrayView<double>     &state,
      const unsigned int           n_sub) const
    {
      if (n_sub == 1)
        {
          // Work on copies: a failed Newton leaves the point as it was.
          SymmetricTensor<2, 3> new_stress = stress;
          double new_state[4];
          std::copy(state.begin(), state.begin() + 4, new_state);
          if (!update_one_step(strain_increment, new_stress, new_state))
            return false;
          stress = new_stress;
          std::copy(new_state, new_state + 4, state.begin());
          return true;
        }
      SymmetricTensor<2, 3>       new_stress = stress;
      double                      new_state[4];
      const SymmetricTensor<2, 3> part = strain_increment / n_sub;
      std::copy(state.begin(), state.begin() + 4, new_state);
      for (unsigned int i = 0; i < n_sub; ++i)
        if (!update_one_step(part, new_stress, new_state))
          return false;
      stress = new_stress;
      std::copy(new_state, new_state + 4, state.begin());
      return true;
    }


    bool
    ModifiedCamClay::update_one_step(
      const SymmetricTensor<2, 3> &strain_increment,
      SymmetricTensor<2, 3>       &stress,
      double                      *state) const
    {
      const double                M2  = M * M;
      const double                v   = state[specific_volume];
      const double                p_n = -trace(stress) / 3.;
      const SymmetricTensor<2, 3> s_n = deviator(stress);
      double                      p_c = state[preconsolidation_pressure];

      // Normally consolidated at a start outside the surface.
      if (p_n > 0)
        {
          const double q_n = von_mises(s_n);
          if (q_n * q_n / M2 + p_n * (p_n - p_c) > 0)
            p_c = p_n + q_n * q_n / (M2 * p_n);
        }

      // Elastic predictor: the exact integral of K = v p / kappa, G at the
      // start of the step.
      const double G = shear_modulus(bulk_modulus(p_n, v));
      const double d = -trace(strain_increment);
      const SymmetricTensor<2, 3> s_trial =
        s_n + 2 * G * deviator(strain_increment);
      const double q_trial = von_mises(s_trial);
      const double p_trial = elastic_pressure(p_n, d, v);
      const double v_new   = v * std::exp(-d);

      state[specific_volume] = v_new;

      if (!(p_trial > 0))
        {
          // No tension: the apex sigma = 0. The elastic part of the
          // volumetric strain is the one that takes p_n to 0 (the
          // inverse of elastic_pressure()); the rest and all of the shear
          // are plastic.
          const double c       = v / kappa;
          const double p_min   = minimum_pressure;
          const double d_elastic =
            p_n > p_min ? (std::log(p_min / p_n) - 1) / c : -p_n / (c * p_min);
          stress = 0;
          state[preconsolidation_pressure] = p_c;
          state[plastic_shear_strain] += q_trial / (3 * G);
          state[plastic_volumetric_strain] += d_elastic - d;
          return true;
        }

      const double f_trial =
        q_trial * q_trial / M2 + p_trial * (p_trial - p_c);
      if (f_trial <= tolerance * p_c * p_c)
        {
          stress = s_trial - p_trial * unit_symmetric_tensor<3>();
          state[preconsolidation_pressure] = p_c;
          return true;
        }

      // Return: unknowns x (the plastic volumetric strain, compression
      // positive) and g (the plastic multiplier). With them
      //   p   = elastic_pressure(p_trial, -x)   (exact elastic law),
      //   p_c = p_c,n exp(v x / (lambda - kappa))   (exact hardening),
      //   q   = q_trial / (1 + 6 G g / M^2)   (the radial return of q),
      // and the residuals are the flow rule x = g df/dp = g (2 p - p_c)
      // and the consistency condition f(p, q, p_c) = 0.
      const double c_elastic   = v / kappa;
      const double c_hardening = v / (lambda - kappa);
      const double strain_tol  = tolerance / c_elastic;
      double       x = 0, g = 0;
      double       p = p_trial, q = q_trial, p_c_new = p_c;
      bool         converged = false;
      for (unsigned int it = 0; it <= max_iterations; ++it)
        {
          p                  = elastic_pressure(p_trial, -x, v);
          p_c_new            = p_c * std::exp(c_hardening * x);
          const double a     = 1 + 6 * G * g / M2;
          q                  = q_trial / a;
          const double r1    = x - g * (2 * p - p_c_new);
          const double r2    = q * q / M2 + p * (p - p_c_new);
          if (!std::isfinite(r1) || !std::isfinite(r2) || !(a > 0))
            break;
          if (std::abs(r1) <= strain_tol &&
              std::abs(r2) <= tolerance * p_c_new * p_c_new)
            {
              converged = true;
              break;
            }
          if (it == max_iterations)
            break;
          const double dp_dx  = -c_elastic * std::max(p, minimum_pressure);
          const double dpc_dx = c_hardening * p_c_new;
          const double dq_dg  = -q * 6 * G / (M2 * a);
          const double J11    = 1 - g * (2 * dp_dx - dpc_dx);
          const double J12    = -(2 * p - p_c_new);
          const double J21    = (2 * p - p_c_new) * dp_dx - p * dpc_dx;
          const double J22    = 2 * q / M2 * dq_dg;
          const double det    = J11 * J22 - J12 * J21;
          if (!(std::abs(det) > 0))
            break;
          x += (-r1 * J22 + J12 * r2) / det;
          g += (-J11 * r2 + J21 * r1) / det;
          // A negative multiplier has no meaning (and 1 + 6 G g / M^2
          // could vanish): back to the elastic side of zero.
          g = std::max(g, 0.);
        }
      if (!converged)
        return false;

      stress = (q_trial > 0 ? q / q_trial : 0.) * s_trial -
               p * unit_symmetric_tensor<3>();
      state[preconsolidation_pressure] = p_c_new;
      state[plastic_shear_strain] += 2 * g * q / M2;
      state[plastic_volumetric_strain] -= x;
      return true;
    }


    double
    ModifiedCamClay::strain_energy_density(
      const SymmetricTensor<2, 3> &stress) const
    {
      const double p = -trace(stress) / 3.;
      const double q = von_mises(deviator(stress));
      const double K = bulk_modulus(p, 1 + initial_void_ratio);
      const double G = shear_modulus(K);
      return 0.5 * (p * p / K + q * q / (3 * G));
    }


    double
    ModifiedCamClay::p_wave_modulus() const
    {
      const double K = bulk_modulus(initial_preconsolidation_pressure,
                                    1 + initial_void_ratio);
      return K + 4. / 3. * shear_modulus(K);
    }


    double
    ModifiedCamClay::p_wave_modulus_at_state(
      const SymmetricTensor<2, 3>   &stress,
      const ArrayView<const double> &state) const
    {
      AssertIndexRange(specific_volume, state.size());
      const double K =
        bulk_modulus(-trace(stress) / 3., state[specific_volume]);
      return K + 4. / 3. * shear_modulus(K);
    }


    double
    ModifiedCamClay::default_k0() const
    {
      return poisson_ratio / (1 - poisson_ratio);
    }


    unsigned int
    ModifiedCamClay::n_state_variables() const
    {
      return 4;
    }


    std::vector<std::string>
    ModifiedCamClay::state_variable_names() const
    {
      return {"preconsolidation_pressure",
              "specific_volume",
              "plastic_shear_strain",
              "plastic_volumetric_strain"};
    }


    void
    ModifiedCamClay::initialize_state(const ArrayView<double> &state) const
    {
      AssertIndexRange(plastic_volumetric_strain, state.size());
      state[preconsolidation_pressure]  = initial_preconsolidation_pressure;
      state[specific_volume]            = 1 + initial_void_ratio;
      state[plastic_shear_strain]       = 0;
      state[plastic_volumetric_strain]  = 0;
    }
  } // namespace MaterialModels
} // namespace MPM

MPM_REGISTER_MATERIAL_MODEL(
  MPM::MaterialModels::ModifiedCamClay,
  "modified cam clay",
  "Modified Cam-Clay (critical state clay, hypoelastic K = v p / kappa, "
  "associated flow, hardening with the plastic volumetric strain).")

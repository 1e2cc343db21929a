#include <deal.II/base/mpi.h>

#include <mpm/base/input_error.h>
#include <mpm/boundary_conditions/coulomb_friction.h>
#include <mpm/material_points/property_layout.h>
#include <mpm/postprocess/column_collapse.h>
#include <mpm/postprocess/energy_balance.h>
#include <mpm/postprocess/flume.h>
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
     * The 1D-like vibrating elastic bar (Bardenhagen 2002): a bar of length
     * L along x, fixed at x = 0, free at x = L, started with the first mode's
     * velocity v0 sin(beta x), beta = pi / (2 L). Its centre-of-mass
     * velocity is v_cm(t) = (2 v0 / pi) cos(omega t) with omega = beta
     * sqrt(E / rho). Reports v_cm against that at output times, the largest
     * deviation relative to 2 v0 / pi, and the period measured from the
     * zero crossings of v_cm against 2 pi / omega. The wave speed is that
     * of the first material, which must have nu = 0.
     */
    template <int dim>
    class VibratingBar : public Postprocessor<dim>
    {
    public:
      static void
      declare_parameters(ParameterHandler &prm)
      {
        prm.declare_entry("Bar length", "25", Patterns::Double(0), "L in m.");
        prm.declare_entry("Velocity amplitude",
                          "0.1",
                          Patterns::Double(0),
                          "v0 in m/s.");
      }

      void
      parse_parameters(ParameterHandler &prm) override
      {
        length = prm.get_double("Bar length");
        v0     = prm.get_double("Velocity amplitude");
      }

      void
      initialize(const Simulator<dim> &simulator) override
      {
        // With nu = 0 the P-wave speed sqrt((lambda + 2 mu) / rho) is the
        // bar speed sqrt(E / rho).
        omega     = M_PI / (2 * length) * simulator.get_materials()[0].wave_speed();
        amplitude        = 2 * v0 / M_PI;
      }

      void
      execute(const Simulator<dim> &simulator, const bool output_step) override
      {
        const auto   s     = simulator.compute_statistics();
        const double v     = s.mean_velocity[0];
        const double exact = amplitude * std::cos(omega * s.time);
        max_error = std::max(max_error, std::abs(v - exact) / amplitude);
        if (last_time >= 0 && (last_v > 0) != (v > 0))
          crossings.push_back(last_time +
                              (s.time - last_time) * last_v / (last_v - v));
        last_time = s.time;
        last_v    = v;
        if (output_step)
          {
            std::ostringstream line;
            line << std::setw(12) << s.time << std::setw(14) << v
                 << std::setw(14) << exact << std::setw(14)
                 << (v - exact) / amplitude << '\n';
            table += line.str();
          }
      }

      void
      write_report(const Simulator<dim> &, std::ostream &report) override
      {
        const double period = 2 * M_PI / omega;
        report << "## vibrating bar: centre-of-mass velocity against "
                  "(2 v0/pi) cos(omega t)\n"
               << "# time (s)   v_cm mpm (m/s)  v_cm exact (m/s)  error / "
                  "(2 v0/pi)\n"
               << table;
        report << "max |v_cm error| / (2 v0/pi): " << max_error << '\n';
        if (crossings.size() >= 2)
          {
            const double measured = 2 * (crossings[1] - crossings[0]);
            report << "period mpm (s): " << measured
                   << "\nperiod exact (s): " << period
                   << "\nperiod relative error: "
                   << (measured - period) / period << '\n';
          }
        else
          report << "period: fewer than two zero crossings of v_cm\n";
      }

      void
      save_state(std::ostream &out) const override
      {
        save_object(out, *this);
      }

      void
      load_state(std::istream &in) override
      {
        load_object(in, *this);
      }

      /**
       * The state accumulated over the run (checkpoints).
       */
      template <class Archive>
      void
      serialize(Archive &ar, const unsigned int)
      {
        ar & omega & amplitude & max_error & last_time & last_v & crossings & table;
      }

    private:
      double              length = 25, v0 = 0.1;
      double              omega = 1, amplitude = 1;
      double              max_error = 0, last_time = -1, last_v = 0;
      std::vector<double> crossings;
      std::string         table;
    };


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
      execute(const Simulator<dim> &, const bool) override
      {}

      void
      write_report(const Simulator<dim> &simulator, std::ostream &report) override
      {
        using Layout   = PropertyLayout<dim>;
        const double g = simulator.get_time_stepping().gravity[dim - 1];
        // Volume-weighted sums per horizontal layer of thickness
        // base_layer: [volume, sigma_yy, exact], the L2 sums, and the
        // column's mass and volume.
        const unsigned int  n_layers = std::ceil(height / base_layer - 1e-9);
        std::vector<double> sums(3 * n_layers + 4, 0.);
        double              rho_ref = 0, modulus = 0;
        for (const auto &point : simulator.get_particle_handler())
          {
            const auto      props = point.get_properties();
            const Material &material =
              simulator.get_materials()
                [static_cast<unsigned int>(props[Layout::material_id])];
            rho_ref = material.density;
            modulus = material.model->p_wave_modulus();
          }
        const MPI_Comm comm = simulator.get_mpi_communicator();
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
        for (const auto &point : simulator.get_particle_handler())
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


    /**
     * Conservation of mass and momentum: mass must stay exactly constant
     * and the momentum change must equal the impulse of gravity, M g t (no
     * boundary forces act on a free-falling body). Reports both errors at
     * output times and their maxima over the run, and the relative change
     * of total energy (kinetic + strain + gravitational).
     */
    template <int dim>
    class Conservation : public Postprocessor<dim>
    {
    public:
      static void
      declare_parameters(ParameterHandler &)
      {}

      void
      initialize(const Simulator<dim> &simulator) override
      {
        const auto s = simulator.compute_statistics();
        mass0        = s.mass;
        momentum0    = s.momentum;
        // sum_p m_p |v_p| would be the natural scale without gravity; the
        // statistics hold M times the mean speed, the same for a body in
        // uniform motion, and not zero for bodies colliding head-on.
        momentum_scale0 = s.mass * s.mean_speed;
        energy0 =
          s.kinetic_energy + s.strain_energy + s.gravitational_potential_energy;
        time0 = s.time;
        const auto spin = simulator.spin_angular_momentum(Point<dim>(s.centre_of_mass),
                                                          s.mean_velocity);
        angular_momentum0 = spin.first;
        angular_momentum_scale0 = spin.second;
      }

      void
      execute(const Simulator<dim> &simulator, const bool output_step) override
      {
        const auto     s = simulator.compute_statistics();
        const auto     g = simulator.get_time_stepping().gravity;
        const double   t = s.time - time0;
        const Tensor<1, dim> expected = momentum0 + mass0 * g * t;
        const double mass_error = std::abs(s.mass - mass0) / mass0;
        // Relative to the impulse of gravity, or without gravity to the
        // initial momentum scale M |v|_mean.
        const double momentum_scale =
          g.norm() > 0 ? mass0 * g.norm() * t : momentum_scale0;
        const double momentum_error =
          (s.momentum - expected).norm() / std::max(1e-300, momentum_scale);
        const double energy = s.kinetic_energy + s.strain_energy +
                              s.gravitational_potential_energy;
        const double energy_scale = std::max(std::abs(energy0), mass0 * g.norm() * g.norm() * t * t / 2);
        const double energy_change = (energy - energy0) / energy_scale;
        max_mass_error     = std::max(max_mass_error, mass_error);
        max_momentum_error = std::max(max_momentum_error, momentum_error);
        max_energy_change  = std::max(max_energy_change, std::abs(energy_change));
        // Spin: angular momentum about the moving centre of mass, which
        // uniform gravity does not change.
        const auto spin = simulator.spin_angular_momentum(Point<dim>(s.centre_of_mass),
                                                          s.mean_velocity);
        const double angular_momentum_error =
          (spin.first - angular_momentum0).norm() /
          std::max({1e-300, angular_momentum_scale0, spin.second});
        max_angular_momentum_error =
          std::max(max_angular_momentum_error, angular_momentum_error);
        if (output_step)
          {
            std::ostringstream line;
            line << std::setw(12) << s.time << std::setw(14) << mass_error
                 << std::setw(14) << momentum_error << std::setw(14)
                 << energy_change << std::setw(14) << angular_momentum_error
                 << '\n';
            table += line.str();
          }
      }

      void
      write_report(const Simulator<dim> &, std::ostream &report) override
      {
        report << "## conservation: mass and momentum against M0 and p0 + M0 "
                  "g t\n"
               << "# time (s)   |M - M0|/M0  |p - p0 - M0 g t|/(M0 g t, or M0 |v|_mean,0 if g = 0)  "
                  "energy change / max(|E0|, M0 g^2 t^2 / 2)  |L - L0| / "
                  "sum m |x - x_c| |v| (at t0, or now if larger; L about the centre of "
                  "mass x_c)\n"
               << table << "max mass error: " << max_mass_error
               << "\nmax momentum error: " << max_momentum_error
               << "\nmax energy change: " << max_energy_change
               << "\nmax angular momentum error: " << max_angular_momentum_error
               << '\n';
      }

      void
      save_state(std::ostream &out) const override
      {
        save_object(out, *this);
      }

      void
      load_state(std::istream &in) override
      {
        load_object(in, *this);
      }

      /**
       * The state accumulated over the run (checkpoints).
       */
      template <class Archive>
      void
      serialize(Archive &ar, const unsigned int)
      {
        ar & mass0 & energy0 & time0 & momentum0 & momentum_scale0 & max_mass_error & max_momentum_error & max_energy_change & table &
          angular_momentum0 & angular_momentum_scale0 &
          max_angular_momentum_error;
      }

    private:
      double             mass0 = 0, energy0 = 0, time0 = 0;
      Tensor<1, dim>     momentum0;
      double             momentum_scale0 = 0;
      double             max_mass_error = 0, max_momentum_error = 0,
                         max_energy_change = 0;
      Tensor<1, 3>       angular_momentum0;
      double             angular_momentum_scale0    = 0;
      double             max_angular_momentum_error = 0;
      std::string        table;
    };


    /**
     * A rigid block sliding down an incline of angle theta under gravity
     * on a frictional bed (the paper's "Rigid Block"). The reference is the
     * closed form of the bed's basal law (BasalLaw::rigid_block_motion()):
     * with Coulomb friction mu, while mu < tan(theta) the block accelerates
     * at a = g (sin theta - mu cos theta), v = a t, s = a t^2 / 2; otherwise
     * it sticks (a = 0); with Voellmy friction it tends to a terminal
     * speed that depends on the block's thickness. Reports
     * the speed of the block (magnitude of its mean velocity) and the
     * distance travelled by its centre of mass against v and s at output
     * times, with relative errors, and the largest relative speed error
     * over t >= 'Error from time', and the largest angle between the
     * mean velocity and the dip direction (gravity's component along the
     * bed): in 3D, on an oblique incline, the block must slide straight
     * down it. mu is read from the bed boundary, so that a sweep over mu
     * changes one parameter.
     */
    template <int dim>
    class SlidingBlock : public Postprocessor<dim>
    {
    public:
      static void
      declare_parameters(ParameterHandler &prm)
      {
        prm.declare_entry("Slope angle",
                          "30",
                          Patterns::Double(0, 90),
                          "Angle theta of the incline to the horizontal "
                          "(normal to gravity), in degrees.");
        prm.declare_entry("Bed boundary",
                          "bed",
                          Patterns::Anything(),
                          "Name of the frictional boundary the block slides "
                          "on (from 'Boundary conditions/List of "
                          "boundaries').");
        prm.declare_entry("Error from time",
                          "0.1",
                          Patterns::Double(0),
                          "Relative errors are maximised over t >= this (s): "
                          "at t -> 0 the reference speed vanishes.");
        prm.declare_entry("Block thickness",
                          "1",
                          Patterns::Double(0),
                          "The block's thickness normal to the bed (m): the "
                          "reference of a rate-dependent basal law (Voellmy's "
                          "drag acts on the block's base, its weight grows "
                          "with its thickness).");
      }

      void
      parse_parameters(ParameterHandler &prm) override
      {
        theta      = prm.get_double("Slope angle") * M_PI / 180;
        bed        = prm.get("Bed boundary");
        error_from = prm.get_double("Error from time");
        thickness  = prm.get_double("Block thickness");
      }

      void
      initialize(const Simulator<dim> &simulator) override
      {
        law = bed_law(simulator);
        const double mu = law->friction_coefficient();
        g               = simulator.get_time_stepping().gravity.norm();
        acceleration    = std::max(0., g * (std::sin(theta) - mu * std::cos(theta)));
        // The dip direction: gravity's component along the bed, whose
        // normal is the mean of the frictional nodes' normals (the bed is
        // the scene's only frictional boundary and a plane).
        Tensor<1, dim> normal;
        for (const auto &node :
             simulator.get_boundary_conditions().constrained_nodes())
          if (node.frictional)
            normal += node.normal;
        normal = Utilities::MPI::sum(normal, simulator.get_mpi_communicator());
        const Tensor<1, dim> gravity = simulator.get_time_stepping().gravity;
        dip = normal.norm() > 0 ?
                gravity - (gravity * normal) / normal.norm_square() * normal :
                Tensor<1, dim>();
        if (dip.norm() > 0)
          dip /= dip.norm();
        const auto s    = simulator.compute_statistics();
        x0              = s.centre_of_mass;
        t0              = s.time;
        std::ostringstream header;
        header << "## sliding block: theta = " << theta * 180 / M_PI
                      << " deg, mu = " << mu
                      << ", a = g (sin theta - mu cos theta) = "
                      << acceleration << " m/s^2"
                      << (acceleration == 0 ? " (sticks)" : "") << '\n';
        if (law->rate_dependent())
          header << "## basal law: " << law->description()
                 << "; block thickness " << thickness
                 << " m, terminal speed (m/s): "
                 << law->rigid_block_motion(1e6, g, theta, thickness).first
                 << '\n';
        report_header = header.str();
      }

      void
      execute(const Simulator<dim> &simulator, const bool output_step) override
      {
        const auto   s        = simulator.compute_statistics();
        const double t        = s.time - t0;
        const double v        = s.mean_velocity.norm();
        const double d        = (s.centre_of_mass - x0).norm();
        // A resumed run does not call initialize().
        if (law == nullptr)
          law = bed_law(simulator);
        const auto [v_exact, d_exact] =
          law->rigid_block_motion(t, g, theta, thickness);
        const double v_error  = v_exact > 0 ? (v - v_exact) / v_exact : v;
        const double d_error  = d_exact > 0 ? (d - d_exact) / d_exact : d;
        if (t >= error_from * (1 - 1e-12))
          {
            max_v_error = std::max(max_v_error, std::abs(v_error));
            max_d_error = std::max(max_d_error, std::abs(d_error));
            if (acceleration > 0 && v > 0)
              {
                // atan2 of the off-dip and along-dip speeds: well
                // conditioned at small angles, where acos is not.
                const double along = s.mean_velocity * dip;
                const double off   = (s.mean_velocity - along * dip).norm();
                max_angle =
                  std::max(max_angle, std::atan2(off, along) * 180 / M_PI);
              }
            // Sums of the least-squares line v = v0 + a t over every step.
            fit[0] += 1;
            fit[1] += t;
            fit[2] += t * t;
            fit[3] += v;
            fit[4] += t * v;
          }
        if (output_step)
          {
            std::ostringstream line;
            line << std::setw(10) << s.time << std::setw(14) << v
                 << std::setw(14) << v_exact << std::setw(14) << v_error
                 << std::setw(14) << d << std::setw(14) << d_exact
                 << std::setw(14) << d_error << '\n';
            table += line.str();
          }
      }

      void
      write_report(const Simulator<dim> &, std::ostream &report) override
      {
        const bool sticks = acceleration == 0;
        report << report_header
               << "# time (s)  speed mpm (m/s)  exact (m/s)  "
               << (sticks ? "abs error (m/s)" : "rel error")
               << "  distance mpm (m)  exact (m)  "
               << (sticks ? "abs error (m)" : "rel error") << '\n'
               << table << "max " << (sticks ? "abs" : "relative")
               << " speed error for t >= " << error_from
               << " s: " << max_v_error << "\nmax "
               << (sticks ? "abs" : "relative")
               << " distance error for t >= " << error_from
               << " s: " << max_d_error << '\n';
        if (!sticks)
          report << "max angle between the mean velocity and the dip "
                    "direction for t >= "
                 << error_from << " s (deg): " << max_angle << '\n';
        // The slope separates the acceleration, which friction decides,
        // from a constant velocity offset picked up in the first steps,
        // whose relative error decays like 1/t.
        const double det = fit[0] * fit[2] - fit[1] * fit[1];
        if (fit[0] > 2 && det > 0 && !law->rate_dependent())
          {
            const double slope  = (fit[0] * fit[4] - fit[1] * fit[3]) / det;
            const double offset = (fit[3] - slope * fit[1]) / fit[0];
            report << "least-squares fit v = v0 + a t over every step with "
                      "t >= "
                   << error_from << " s:\nfitted a (m/s^2): " << slope
                   << (sticks ? "\nfitted a abs error (m/s^2): " :
                                "\nfitted a rel error: ")
                   << (sticks ? slope : (slope - acceleration) / acceleration)
                   << "\nfitted v0 (m/s): " << offset << '\n';
          }
      }

      void
      save_state(std::ostream &out) const override
      {
        save_object(out, *this);
      }

      void
      load_state(std::istream &in) override
      {
        load_object(in, *this);
      }

      /**
       * The state accumulated over the run (checkpoints).
       */
      template <class Archive>
      void
      serialize(Archive &ar, const unsigned int)
      {
        ar & acceleration & t0 & x0 & max_v_error & max_d_error & fit & table &
          report_header & dip & max_angle & g;
      }

    private:
      /// The bed's basal law; a bed that is not frictional slides without
      /// friction.
      const BasalLaw<dim> *
      bed_law(const Simulator<dim> &simulator) const
      {
        const BasalLaw<dim> *bed_law =
          simulator.get_boundary_conditions().basal_law(bed);
        return bed_law != nullptr ? bed_law : &frictionless;
      }

      const CoulombFriction<dim> frictionless{0.};
      double             theta = 0, error_from = 0.1, acceleration = 0, t0 = 0;
      double             thickness = 1, g = 0;
      std::string        bed;
      /// The bed's basal law (the Simulator's, alive for the whole run).
      const BasalLaw<dim> *law = nullptr;
      Point<dim>         x0;
      double             max_v_error = 0, max_d_error = 0;
      /// Unit vector down the bed's steepest slope, and the largest angle
      /// (degrees) between it and the block's mean velocity.
      Tensor<1, dim>     dip;
      double             max_angle = 0;
      std::array<double, 5> fit{};
      std::string        table, report_header;
    };


    std::string
    names()
    {
      return "vibrating bar|self-weight column|conservation|sliding block|"
             "flume|column collapse|energy balance";
    }


    template <int dim>
    void
    declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Postprocess");
      prm.enter_subsection("vibrating bar");
      VibratingBar<dim>::declare_parameters(prm);
      prm.leave_subsection();
      prm.enter_subsection("self-weight column");
      SelfWeightColumn<dim>::declare_parameters(prm);
      prm.leave_subsection();
      prm.enter_subsection("conservation");
      Conservation<dim>::declare_parameters(prm);
      prm.leave_subsection();
      prm.enter_subsection("sliding block");
      SlidingBlock<dim>::declare_parameters(prm);
      prm.leave_subsection();
      prm.enter_subsection("flume");
      Flume<dim>::declare_parameters(prm);
      prm.leave_subsection();
      prm.enter_subsection("column collapse");
      ColumnCollapse<dim>::declare_parameters(prm);
      prm.leave_subsection();
      prm.enter_subsection("energy balance");
      EnergyBalance<dim>::declare_parameters(prm);
      prm.leave_subsection();
      prm.leave_subsection();
    }


    template <int dim>
    std::unique_ptr<Postprocessor<dim>>
    create(const std::string &name, ParameterHandler &prm)
    {
      std::unique_ptr<Postprocessor<dim>> p;
      if (name == "vibrating bar")
        p = std::make_unique<VibratingBar<dim>>();
      else if (name == "self-weight column")
        p = std::make_unique<SelfWeightColumn<dim>>();
      else if (name == "conservation")
        p = std::make_unique<Conservation<dim>>();
      else if (name == "sliding block")
        p = std::make_unique<SlidingBlock<dim>>();
      else if (name == "flume")
        p = std::make_unique<Flume<dim>>();
      else if (name == "column collapse")
        p = std::make_unique<ColumnCollapse<dim>>();
      else if (name == "energy balance")
        p = std::make_unique<EnergyBalance<dim>>();
      else
        throw InputError("Unknown postprocessor '" + name + "'.");
      prm.enter_subsection("Postprocess");
      prm.enter_subsection(name);
      p->parse_parameters(prm);
      prm.leave_subsection();
      prm.leave_subsection();
      return p;
    }


    template void
    declare_parameters<2>(ParameterHandler &);
    template void
    declare_parameters<3>(ParameterHandler &);
    template std::unique_ptr<Postprocessor<2>>
    create<2>(const std::string &, ParameterHandler &);
    template std::unique_ptr<Postprocessor<3>>
    create<3>(const std::string &, ParameterHandler &);
  } // namespace Postprocessors
} // namespace MPM

#include <deal.II/base/mpi.h>

#include <mpm/base/input_error.h>
#include <mpm/boundary_conditions/coulomb_friction.h>
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
    class SlidingBlock : public PostprocessorWithState<dim, SlidingBlock<dim>>
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
        prm.declare_entry("Buoyant block",
                          "false",
                          Patterns::Bool(),
                          "The block is saturated (pore water), its water "
                          "table at its top and the water seeping parallel "
                          "to the bed: the bed's Coulomb friction acts on "
                          "the effective normal stress, the buoyant weight, "
                          "a = g (sin theta - f mu cos theta) with f = "
                          "(rho_sat - rho_w) / rho_sat of the block's "
                          "material (doc/pore_water.md). Coulomb beds only.");
        prm.declare_entry(
          "Excess pore pressure ratio",
          "0",
          Patterns::Double(0, 1),
          "With 'Buoyant block': the share lambda of the buoyant "
          "overburden that an excess pore pressure carries, p = rho_w g "
          "cos(theta) (H - y) + lambda (rho_sat - rho_w) g cos(theta) (H - "
          "y), held by a permeability too low to drain it within the run "
          "(a liquefied layer as lambda -> 1): f = (1 - lambda) (rho_sat - "
          "rho_w) / rho_sat. It tests the wall's pore pressure where the "
          "pressure's gradient normal to the bed is not hydrostatic "
          "(doc/pore_water.md, 'Friction in effective stress').");
        prm.declare_entry(
          "Side-wall resistance",
          "0",
          Patterns::Double(0),
          "With 'Boundary conditions/Side walls' (a channel of width W, "
          "wall friction mu_w): the walls' friction as a share of the "
          "block's weight normal to the bed, r = mu_w k H / W for a block of "
          "thickness H whose out-of-plane stress sigma_zz is k times the "
          "overburden normal to the bed: a = g (sin theta - (mu + r) cos "
          "theta) (doc/boundary_conditions.md, 'Side-wall friction'). A "
          "buoyant block's sigma_zz is effective, k times the buoyant "
          "overburden: r = f mu_w k H / W and a = g (sin theta - (f mu + r) "
          "cos theta). Coulomb beds only.");
      }

      void
      parse_parameters(ParameterHandler &prm) override
      {
        theta        = prm.get_double("Slope angle") * M_PI / 180;
        bed          = prm.get("Bed boundary");
        error_from   = prm.get_double("Error from time");
        thickness    = prm.get_double("Block thickness");
        buoyant      = prm.get_bool("Buoyant block");
        excess_ratio = prm.get_double("Excess pore pressure ratio");
        check_input(excess_ratio == 0 || buoyant,
                    "Postprocess/sliding block/Excess pore pressure ratio "
                    "needs 'Buoyant block = true'.");
        side_wall_resistance = prm.get_double("Side-wall resistance");
      }

      void
      initialize() override
      {
        law             = bed_law();
        const double mu = law->friction_coefficient();
        g               = this->get_time_stepping().gravity.norm();
        set_reference_gravity();
        acceleration =
          std::max(0.,
                   g * (std::sin(theta) -
                        (f * mu + side_wall_resistance) * std::cos(theta)));
        // The dip direction: gravity's component along the bed, whose
        // normal is the mean of the frictional nodes' normals (the bed is
        // the scene's only frictional boundary and a plane).
        Tensor<1, dim> normal;
        for (const auto &node :
             this->get_boundary_conditions().constrained_nodes())
          if (node.frictional)
            normal += node.normal;
        normal = Utilities::MPI::sum(normal, this->get_mpi_communicator());
        const Tensor<1, dim> gravity = this->get_time_stepping().gravity;
        dip = normal.norm() > 0 ?
                gravity - (gravity * normal) / normal.norm_square() * normal :
                Tensor<1, dim>();
        if (dip.norm() > 0)
          dip /= dip.norm();
        const auto s    = this->compute_statistics();
        x0              = s.centre_of_mass;
        t0              = s.time;
        std::ostringstream header;
        // The reference's formula as used: f for a buoyant block, r for
        // side walls.
        const std::string friction = buoyant ? "f mu" : "mu";
        const std::string resistance =
          side_wall_resistance > 0 ? "(" + friction + " + r)" : friction;
        header << "## sliding block: theta = " << theta * 180 / M_PI
               << " deg, mu = " << mu
               << (buoyant ? ", buoyant: f = " + std::to_string(f) : "")
               << (side_wall_resistance > 0 ?
                     ", side walls r = " +
                       std::to_string(side_wall_resistance) :
                     "")
               << ", a = g (sin theta - " << resistance
               << " cos theta) = " << acceleration << " m/s^2"
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
      execute(const bool output_step) override
      {
        const auto   s        = this->compute_statistics();
        const double t        = s.time - t0;
        const double v        = s.mean_velocity.norm();
        const double d        = (s.centre_of_mass - x0).norm();
        // A resumed run does not call initialize().
        if (law == nullptr)
          {
            law = bed_law();
            set_reference_gravity();
          }
        // A buoyant block: Coulomb's law on the buoyant weight is that of
        // a dry block under a gravity g' whose normal part is f times
        // smaller, g' (sin theta', cos theta') = g (sin theta, f cos theta).
        // With side walls (a Coulomb bed), the constant acceleration of
        // initialize().
        const auto [v_exact, d_exact] =
          side_wall_resistance > 0 ?
            std::pair<double, double>(acceleration * t,
                                      0.5 * acceleration * t * t) :
            law->rigid_block_motion(t, g_reference, theta_reference, thickness);
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
      write_report(std::ostream &report) override
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
      /// f and the reference block's gravity and slope (theta and g for
      /// a dry block).
      void
      set_reference_gravity()
      {
        f = 1;
        check_input(side_wall_resistance == 0 || !law->rate_dependent(),
                    "Postprocess/sliding block/Side-wall resistance needs a "
                    "Coulomb bed.");
        if (buoyant)
          {
            check_input(!law->rate_dependent(),
                        "Postprocess/sliding block/Buoyant block = true "
                        "needs a Coulomb bed.");
            const auto &water = this->get_pore_water();
            check_input(water.active(),
                        "Postprocess/sliding block/Buoyant block = true "
                        "needs a saturated material (Porosity > 0).");
            const auto &materials = this->get_materials();
            for (unsigned int m = 0; m < materials.size(); ++m)
              if (materials[m].porosity > 0)
                {
                  const double rho_sat =
                    materials[m].density +
                    materials[m].porosity * water.density();
                  f = (1 - excess_ratio) * (rho_sat - water.density()) /
                      rho_sat;
                  break;
                }
          }
        // A dry block's reference is its own theta and g, bit for bit.
        theta_reference =
          buoyant ? std::atan2(std::sin(theta), f * std::cos(theta)) : theta;
        g_reference =
          buoyant ? g * std::hypot(std::sin(theta), f * std::cos(theta)) : g;
      }

      bool   buoyant         = false;
      double excess_ratio    = 0;
      double f               = 1;
      double theta_reference = 0;
      double g_reference     = 0;

      /// The bed's basal law; a bed that is not frictional slides without
      /// friction.
      const BasalLaw<dim> *
      bed_law() const
      {
        const BasalLaw<dim> *bed_law =
          this->get_boundary_conditions().basal_law(bed);
        return bed_law != nullptr ? bed_law : &frictionless;
      }

      const CoulombFriction<dim> frictionless{0.};
      double             theta = 0, error_from = 0.1, acceleration = 0, t0 = 0;
      double             thickness = 1, g = 0;
      /// The side walls' friction as a share of the weight normal to the bed.
      double             side_wall_resistance = 0;
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
  } // namespace Postprocessors
} // namespace MPM

MPM_REGISTER_POSTPROCESSOR(MPM::Postprocessors::SlidingBlock,
                           "sliding block",
                           "a block sliding on an incline against the closed form of its bed's basal law.")

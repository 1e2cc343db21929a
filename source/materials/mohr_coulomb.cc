#include <mpm/base/input_error.h>
#include <mpm/base/units.h>
#include <mpm/materials/frictional_strength.h>
#include <mpm/materials/mohr_coulomb.h>
#include <mpm/materials/principal_stresses.h>

#include <algorithm>
#include <bitset>
#include <cmath>
#include <tuple>

namespace MPM
{
  namespace MaterialModels
  {
    namespace
    {
      /**
       * sqrt(2/3 |dev(ds)|^2) of principal values @p ds. Times 1 / (2 G)
       * it is the equivalent plastic shear strain of a stress change ds
       * returned by the elastic law: the deviator of
       * ((1 + nu) ds - nu tr(ds) I) / E is dev(ds) / (2 G).
       */
      double
      deviatoric_norm(const std::array<double, 3> &ds)
      {
        const double mean = (ds[0] + ds[1] + ds[2]) * (1. / 3.);
        double       e2   = 0;
        for (unsigned int i = 0; i < 3; ++i)
          e2 += (ds[i] - mean) * (ds[i] - mean);
        return std::sqrt(2. / 3. * e2);
      }

      std::string
      mohr_coulomb_parameter(const std::string &entry)
      {
        return "mohr coulomb/" + entry;
      }

      /**
       * Solve the m x m system A x = b (m <= 3) by Gaussian elimination with
       * partial pivoting. False if a pivot is negligible against the
       * largest entry: the candidate set is then not independent (for
       * instance the three shear planes at the apex with psi = 0, whose
       * flow directions are linearly dependent) and is skipped.
       */
      bool
      solve(std::array<std::array<double, 3>, 3> A,
            std::array<double, 3>                b,
            const unsigned int                   m,
            std::array<double, 3>               &x)
      {
        double a_max = 0;
        for (unsigned int i = 0; i < m; ++i)
          for (unsigned int j = 0; j < m; ++j)
            a_max = std::max(a_max, std::abs(A[i][j]));
        if (a_max == 0)
          return false;
        for (unsigned int k = 0; k < m; ++k)
        {
          unsigned int p = k;
          for (unsigned int i = k + 1; i < m; ++i)
            if (std::abs(A[i][k]) > std::abs(A[p][k]))
              p = i;
          if (std::abs(A[p][k]) < 1e-10 * a_max)
            return false;
          std::swap(A[k], A[p]);
          std::swap(b[k], b[p]);
          for (unsigned int i = k + 1; i < m; ++i)
          {
            const double l = A[i][k] / A[k][k];
            for (unsigned int j = k; j < m; ++j)
              A[i][j] -= l * A[k][j];
            b[i] -= l * b[k];
          }
        }
        for (unsigned int k = m; k-- > 0;)
        {
          double r = b[k];
          for (unsigned int j = k + 1; j < m; ++j)
            r -= A[k][j] * x[j];
          x[k] = r / A[k][k];
        }
        return true;
      }
    } // namespace


    void
    MohrCoulomb::declare_parameters(ParameterHandler &prm)
    {
      IsotropicElasticity::declare_parameters(prm);
      prm.declare_entry("Friction angle",
                        "30",
                        Patterns::Double(0, 90),
                        "Internal friction angle phi in degrees, in (0, 90).");
      prm.declare_entry(
        "Dilation angle",
        "0",
        Patterns::Double(0, 90),
        "Dilation angle psi in degrees, in [0, friction angle]; 0 gives "
        "plastic shearing without volume change (critical state sand), "
        "psi = phi associated flow.");
      prm.declare_entry("Cohesion",
                        "0",
                        Patterns::Double(0),
                        "Cohesion c in Pa, >= 0; 0 for dry sand.");
      prm.declare_entry(
        "Tension cutoff",
        "0",
        Patterns::Double(0),
        "The largest principal stress the material carries, in Pa (tension "
        "positive), >= 0 and at most c cot(phi), where the Mohr-Coulomb "
        "planes meet; 0 for a cohesionless material.");
      prm.enter_subsection("Strain softening");
      {
        prm.declare_entry(
          "Enabled",
          "false",
          Patterns::Bool(),
          "Whether the friction angle, dilation angle and cohesion soften "
          "with the accumulated plastic shear strain kappa: the values above "
          "are the peak ones, reached up to 'Peak plastic shear strain'; "
          "from there they go linearly to the residual ones below, reached "
          "at 'Residual plastic shear strain'. The tension cutoff follows as "
          "min(T, c cot(phi)).");
        prm.declare_entry("Residual friction angle",
                          "30",
                          Patterns::Double(0, 90),
                          "Friction angle at the residual strain, in degrees, "
                          "in (0, peak friction angle].");
        prm.declare_entry("Residual dilation angle",
                          "0",
                          Patterns::Double(0, 90),
                          "Dilation angle at the residual strain, in degrees, "
                          "in [0, min(peak dilation angle, residual friction "
                          "angle)].");
        prm.declare_entry("Residual cohesion",
                          "0",
                          Patterns::Double(0),
                          "Cohesion at the residual strain in Pa, in [0, peak "
                          "cohesion].");
        prm.declare_entry("Peak plastic shear strain",
                          "0",
                          Patterns::Double(0),
                          "The accumulated plastic shear strain at which "
                          "softening starts, >= 0.");
        prm.declare_entry("Residual plastic shear strain",
                          "0.1",
                          Patterns::Double(0),
                          "The accumulated plastic shear strain at which the "
                          "residual strength is reached, > 'Peak plastic shear "
                          "strain'.");
        prm.declare_entry(
          "Reference cell size",
          "0",
          Patterns::Double(0),
          "Regularisation by the cell size (m): the two plastic shear "
          "strains above are those of a point in a background cell of this "
          "size (its shortest vertex distance); in a cell of size h they "
          "are multiplied by this size / h, so that the plastic "
          "displacement across a shear band one cell wide that takes the "
          "soil from peak to residual is the same on every mesh "
          "(doc/slope_stability.md). 0: not regularised, the strains as "
          "given in every cell.");
        prm.declare_entry(
          "Nonlocal radius",
          "0",
          Patterns::Double(0),
          "Non-local regularisation (m): the strength of a point is that of "
          "the regularised plastic shear strain kappa* = (1 - m) kappa + m "
          "kappa_avg, kappa_avg the average of kappa over the points of the "
          "material within this radius, weighted by their volume and by "
          "(1 - r^2 / R^2)^2 (state variable nonlocal_plastic_shear_strain). "
          "The shear bands then have a width set by this radius rather than "
          "by the cells: take it at least two or three cells of the coarsest "
          "mesh you compare (doc/slope_stability.md). Its cost grows with "
          "the radius over the cell size. 0: local (the strength of the "
          "point's own kappa). Not together with 'Reference cell size'.");
        prm.declare_entry(
          "Over-nonlocal factor",
          "2",
          Patterns::Double(1),
          "m in kappa* = (1 - m) kappa + m kappa_avg, >= 1: 1 is the plain "
          "non-local average; m > 1 (over-nonlocal; 2 as in Vermeer and "
          "Brinkgreve 1994 and Galavi and Schweiger 2010) keeps the plastic "
          "zone of a softening material from shrinking to one cell, which "
          "m = 1 does not ensure.");
      }
      prm.leave_subsection();
    }


    void
    MohrCoulomb::parse_parameters(ParameterHandler &prm)
    {
      elasticity.parse_parameters(prm, "mohr coulomb");
      const double phi_degrees = prm.get_double("Friction angle");
      const double psi_degrees = prm.get_double("Dilation angle");
      const double cohesion    = prm.get_double("Cohesion");
      const double tension_cutoff = prm.get_double("Tension cutoff");

      check_frictional_strength("mohr coulomb",
                                phi_degrees,
                                psi_degrees,
                                cohesion,
                                tension_cutoff,
                                "the apex of the Mohr-Coulomb surface");

      peak_strength.friction_angle = phi_degrees * degree;
      peak_strength.dilation_angle = psi_degrees * degree;
      peak_strength.cohesion       = cohesion;
      const double apex = cohesion / std::tan(peak_strength.friction_angle);
      peak_strength.tension_cutoff = std::min(tension_cutoff, apex);

      prm.enter_subsection("Strain softening");
      softening = prm.get_bool("Enabled");
      if (softening)
        {
          const auto entry = [](const std::string &e) {
            return mohr_coulomb_parameter("Strain softening/" + e);
          };
          const double phi_r = prm.get_double("Residual friction angle");
          const double psi_r = prm.get_double("Residual dilation angle");
          const double c_r   = prm.get_double("Residual cohesion");
          softening_start    = prm.get_double("Peak plastic shear strain");
          softening_end      = prm.get_double("Residual plastic shear strain");
          reference_cell_size = prm.get_double("Reference cell size");
          nonlocal.radius     = prm.get_double("Nonlocal radius");
          nonlocal.over_nonlocal_factor =
            prm.get_double("Over-nonlocal factor");
          check_input(!(reference_cell_size > 0 && nonlocal.radius > 0),
                      entry("Reference cell size") + " = " +
                        std::to_string(reference_cell_size) + " and " +
                        entry("Nonlocal radius") + " = " +
                        std::to_string(nonlocal.radius) +
                        ": these are two regularisations of the same "
                        "softening; set one of them to 0.");
          check_input(phi_r > 0 && phi_r <= phi_degrees,
                      entry("Residual friction angle") + " = " +
                        std::to_string(phi_r) +
                        " degrees: must lie in (0, peak friction angle = " +
                        std::to_string(phi_degrees) + "].");
          check_input(psi_r >= 0 && psi_r <= psi_degrees && psi_r <= phi_r,
                      entry("Residual dilation angle") + " = " +
                        std::to_string(psi_r) +
                        " degrees: must lie in [0, min(peak dilation angle "
                        "= " +
                        std::to_string(psi_degrees) +
                        ", residual friction angle = " +
                        std::to_string(phi_r) + ")].");
          check_input(c_r >= 0 && c_r <= cohesion,
                      entry("Residual cohesion") + " = " +
                        std::to_string(c_r) +
                        " Pa: must lie in [0, peak cohesion = " +
                        std::to_string(cohesion) + "].");
          check_input(softening_start >= 0 &&
                        softening_end > softening_start,
                      entry("Residual plastic shear strain") + " = " +
                        std::to_string(softening_end) +
                        ": must be larger than " +
                        entry("Peak plastic shear strain") + " = " +
                        std::to_string(softening_start) + " (>= 0).");
          residual_strength.friction_angle = phi_r * degree;
          residual_strength.dilation_angle = psi_r * degree;
          residual_strength.cohesion       = c_r;
          residual_strength.tension_cutoff =
            std::min(peak_strength.tension_cutoff,
                     c_r / std::tan(residual_strength.friction_angle));
        }
      prm.leave_subsection();
      nonlocal_state = softening && nonlocal.radius > 0;

      inverse_two_shear_modulus = 0.5 / elasticity.shear_modulus;
      given_strength            = peak_strength;
      given_residual_strength   = residual_strength;
      peak                      = make_surfaces(peak_strength, true);
      if (softening)
        residual = make_surfaces(residual_strength, true);
    }


    void
    MohrCoulomb::set_strength_reduction(const double factor)
    {
      Assert(factor > 0, ExcMessage("The strength reduction factor must be > 0."));
      peak_strength = given_strength.reduced(factor);
      peak               = make_surfaces(peak_strength, true);
      if (softening)
        {
          residual_strength = given_residual_strength.reduced(factor);
          // As in parse_parameters(): the residual tension cutoff is at
          // most the peak one and the residual apex (which the reduction
          // keeps in place).
          if (factor != 1.)
            residual_strength.tension_cutoff =
              std::min(peak_strength.tension_cutoff,
                       residual_strength.cohesion /
                         std::tan(residual_strength.friction_angle));
          residual = make_surfaces(residual_strength, true);
        }
    }


    MohrCoulomb::Strength
    MohrCoulomb::strength_at(const double kappa,
                             const double start,
                             const double end) const
    {
      if (!softening || kappa <= start)
        return peak_strength;
      if (kappa >= end)
        return residual_strength;
      const double w = (kappa - start) / (end - start);
      Strength strength;
      strength.friction_angle =
        peak_strength.friction_angle +
        w * (residual_strength.friction_angle - peak_strength.friction_angle);
      strength.dilation_angle =
        peak_strength.dilation_angle +
        w * (residual_strength.dilation_angle - peak_strength.dilation_angle);
      strength.cohesion =
        peak_strength.cohesion +
        w * (residual_strength.cohesion - peak_strength.cohesion);
      strength.tension_cutoff =
        std::min(peak_strength.tension_cutoff,
                 strength.cohesion / std::tan(strength.friction_angle));
      return strength;
    }


    MohrCoulomb::YieldSurfaces
    MohrCoulomb::make_surfaces(const Strength &strength,
                               const bool      prepare_sets) const
    {
      YieldSurfaces surfaces;
      const double  sin_phi = std::sin(strength.friction_angle);
      const double  sin_psi = std::sin(strength.dilation_angle);
      const double  k = 2 * strength.cohesion * std::cos(strength.friction_angle);
      surfaces.tension_cutoff = strength.tension_cutoff;

      // Gradients a and flow directions n in the sorted frame.
      std::array<std::array<double, 3>, 6> flow;
      auto &gradient = surfaces.gradient;
      gradient[0]    = {{1 + sin_phi, 0, -(1 - sin_phi)}};
      flow[0]        = {{1 + sin_psi, 0, -(1 - sin_psi)}};
      gradient[1]    = {{1 + sin_phi, -(1 - sin_phi), 0}};
      flow[1]        = {{1 + sin_psi, -(1 - sin_psi), 0}};
      gradient[2]    = {{0, 1 + sin_phi, -(1 - sin_phi)}};
      flow[2]        = {{0, 1 + sin_psi, -(1 - sin_psi)}};
      for (unsigned int i = 0; i < 3; ++i)
      {
        gradient[3 + i]    = {{0, 0, 0}};
        gradient[3 + i][i] = 1;
        flow[3 + i]        = gradient[3 + i];
      }
      for (unsigned int s = 0; s < 6; ++s)
      {
        surfaces.bound[s] = (s < 3) ? k : strength.tension_cutoff;
        const double tr   = flow[s][0] + flow[s][1] + flow[s][2];
        for (unsigned int i = 0; i < 3; ++i)
          surfaces.return_direction[s][i] =
            elasticity.lambda * tr + 2 * elasticity.shear_modulus * flow[s][i];
        surfaces.shear_strain_per_multiplier[s] =
          deviatoric_norm(surfaces.return_direction[s]) *
          inverse_two_shear_modulus;
      }

      if (prepare_sets)
        {
          surfaces.candidate_sets = candidate_topology();
          for (CandidateSet &set : surfaces.candidate_sets)
            prepare_candidate_set(surfaces, set);
        }
      return surfaces;
    }


    void
    MohrCoulomb::prepare_candidate_set(const YieldSurfaces &surfaces,
                                       CandidateSet        &set)
    {
      if (set.m == 1)
        {
          // One plane: the 1 x 1 case of the general code below, with the
          // same arithmetic (solve() returns 1 / a, and fails exactly when
          // a is 0 or not a number), without its loops and copies: the
          // single planes are most of the sets a softening point's return
          // prepares.
          const auto  &g = surfaces.gradient[set.active[0]];
          const auto  &r = surfaces.return_direction[set.active[0]];
          double       a = 0;
          for (unsigned int d = 0; d < 3; ++d)
            a += g[d] * r[d];
          set.independent   = std::abs(a) > 0;
          set.inverse[0][0] = 1. / a;
          return;
        }
      std::array<std::array<double, 3>, 3> A{};
      for (unsigned int i = 0; i < set.m; ++i)
        for (unsigned int j = 0; j < set.m; ++j)
          for (unsigned int d = 0; d < 3; ++d)
            A[i][j] += surfaces.gradient[set.active[i]][d] *
                       surfaces.return_direction[set.active[j]][d];
      // Column j of the inverse solves A x = e_j; solve() tells a
      // dependent set from the matrix alone.
      set.independent = true;
      for (unsigned int j = 0; j < set.m && set.independent; ++j)
        {
          std::array<double, 3> e{}, column{};
          e[j]            = 1;
          set.independent = solve(A, e, set.m, column);
          for (unsigned int i = 0; i < set.m; ++i)
            set.inverse[i][j] = column[i];
        }
      if (set.m == 3)
        {
          std::array<std::array<double, 3>, 3> G;
          std::array<double, 3>                b;
          for (unsigned int i = 0; i < 3; ++i)
            {
              G[i] = surfaces.gradient[set.active[i]];
              b[i] = surfaces.bound[set.active[i]];
            }
          set.corner_defined = solve(G, b, 3, set.corner);
        }
    }


    const std::vector<MohrCoulomb::CandidateSet> &
    MohrCoulomb::candidate_topology()
    {
      static const std::vector<CandidateSet> topology = []() {
        // Candidate sets of at most three surfaces (three independent
        // planes fix a point in principal space), fewest first: a point on
        // a plane is tried before the edges and the edges before the
        // corners.
        std::vector<CandidateSet> sets;
        for (unsigned int size = 1; size <= 3; ++size)
          for (unsigned int bits = 1; bits < 64; ++bits)
            if (std::bitset<6>(bits).count() == size)
              {
                CandidateSet set;
                set.bits = bits;
                for (unsigned int k = 0; k < 6; ++k)
                  if (bits & (1u << k))
                    set.active[set.m++] = k;
                sets.push_back(set);
              }
        // The main plane (0: s1 - s3, the largest shear) is active in almost
        // every return, so the sets that contain it go first, fewest planes
        // first, and among the pairs the one with the tension cutoff of s1
        // (plane 3) first. In the flume (a replay of 50,780 returns at
        // t = 0.23 s) 62 % of the returns end on the main plane alone and
        // 38 % on the main plane with the cutoff of s1 ({0, 3}: sand at zero
        // confinement near the free surface), under 0.2 % elsewhere. Plane 0
        // first cut the sets tried per plastic point from 4.3 to 1.7; {0, 3}
        // before the edges {0, 1} and {0, 2} cuts it to 1.4. The admissible
        // return is unique, so the order changes the cost, not the result.
        const auto rank = [](const CandidateSet &set) {
          return std::make_tuple(!(set.bits & 1u), set.m, !(set.bits & 8u));
        };
        std::stable_sort(sets.begin(),
                         sets.end(),
                         [&rank](const CandidateSet &a, const CandidateSet &b) {
                           return rank(a) < rank(b);
                         });
        return sets;
      }();
      return topology;
    }


    template <unsigned int m>
    inline DEAL_II_ALWAYS_INLINE bool
    MohrCoulomb::try_candidate_set(const YieldSurfaces         &surfaces,
                                   const CandidateSet          &set,
                                   const std::array<double, 3> &trial,
                                   const std::array<double, 6> &f_trial,
                                   const double                 tol,
                                   const double                 multiplier_tol,
                                   std::array<double, 3>       &x,
                                   double &first_multiplier) const
    {
      // f_k(trial - sum_l dgamma_l r_l) = 0 for every active k.
      std::array<double, 3> dgamma{};
      for (unsigned int i = 0; i < m; ++i)
        for (unsigned int j = 0; j < m; ++j)
          dgamma[i] += set.inverse[i][j] * f_trial[set.active[j]];
      bool negative_multiplier = false;
      for (unsigned int i = 0; i < m; ++i)
        negative_multiplier = negative_multiplier || dgamma[i] < -multiplier_tol;
      if (negative_multiplier)
        return false;
      first_multiplier = dgamma[0];

      x = trial;
      if constexpr (m < 3)
        {
          for (unsigned int j = 0; j < m; ++j)
            for (unsigned int d = 0; d < 3; ++d)
              x[d] -= dgamma[j] * surfaces.return_direction[set.active[j]][d];
        }
      else
        {
          // Three planes fix the point: the planes' own intersection,
          // which puts the apex of a cohesionless material exactly at zero
          // stress instead of at a rounding residue.
          if (!set.corner_defined)
            return false;
          x = set.corner;
        }

      if (x[0] < x[1] - tol || x[1] < x[2] - tol)
        return false;
      bool admissible = true;
      for (unsigned int k = 0; k < 6; ++k)
        admissible = admissible && (surfaces.plane_value(k, x) <= tol);
      if (!admissible)
        return false;

      // Ties within the tolerance are equal principal stresses.
      if (x[0] < x[1])
        x[0] = x[1] = 0.5 * (x[0] + x[1]);
      if (x[1] < x[2])
        x[1] = x[2] = 0.5 * (x[1] + x[2]);
      return true;
    }


    template <bool prepared>
    inline DEAL_II_ALWAYS_INLINE unsigned int
    MohrCoulomb::return_principal_inline(
      const YieldSurfaces   &surfaces,
      std::array<double, 3> &s,
      double                &plastic_shear_increment) const
    {
      plastic_shear_increment = 0;
      const std::array<double, 3> trial = s;
      // The plastic shear strain of a stress change from the trial stress.
      const auto shear_strain_to = [&](const std::array<double, 3> &x) {
        return deviatoric_norm({{trial[0] - x[0], trial[1] - x[1], trial[2] - x[2]}}) *
               inverse_two_shear_modulus;
      };

      const double scale = std::max({std::abs(s[0]),
                                     std::abs(s[1]),
                                     std::abs(s[2]),
                                     surfaces.bound[0],
                                     surfaces.bound[3]});
      const double tol = yield_relative_tolerance * scale;

      std::array<double, 6> f_trial;
      bool                  elastic = true;
      for (unsigned int k = 0; k < 6; ++k)
      {
        f_trial[k] = surfaces.plane_value(k, trial);
        elastic    = elastic && (f_trial[k] <= tol);
      }
      if (elastic)
        return 0;

      // A multiplier is a strain: compare it with the tolerance divided by
      // the stiffness.
      const double multiplier_tol = tol / elasticity.p_wave_modulus();

      // Try one candidate set; on success the returned stress is in s.
      const auto try_set = [&](const CandidateSet &set) {
        std::array<double, 3> x;
        double                dgamma = 0;
        const bool            found =
          set.m == 1 ? try_candidate_set<1>(
                         surfaces, set, trial, f_trial, tol, multiplier_tol, x, dgamma) :
          set.m == 2 ? try_candidate_set<2>(
                         surfaces, set, trial, f_trial, tol, multiplier_tol, x, dgamma) :
                       try_candidate_set<3>(
                         surfaces, set, trial, f_trial, tol, multiplier_tol, x, dgamma);
        if (found)
          {
            s = x;
            plastic_shear_increment =
              set.m == 1 ? std::abs(dgamma) *
                             surfaces.shear_strain_per_multiplier[set.active[0]] :
                           shear_strain_to(x);
          }
        return found;
      };

      if constexpr (prepared)
        {
          for (const CandidateSet &set : surfaces.candidate_sets)
            if (set.independent && try_set(set))
              return set.bits;
        }
      else
        // Surfaces of one return (a softening point): prepare each set
        // when it is tried; most returns end with the first or second.
        for (CandidateSet set : candidate_topology())
          {
            prepare_candidate_set(surfaces, set);
            if (set.independent && try_set(set))
              return set.bits;
          }

      // Not reached for phi in (0, 90) and psi in [0, phi] (the unit test
      // counts it over random trial stresses); the apex of the admissible
      // set is the safe answer.
      const double t = surfaces.tension_cutoff;
      s = {{t, t, t}};
      plastic_shear_increment = shear_strain_to(s);
      return fallback;
    }


    unsigned int
    MohrCoulomb::return_principal(std::array<double, 3> &s) const
    {
      double plastic_shear_increment;
      return return_principal_inline<true>(peak, s, plastic_shear_increment);
    }


    bool
    MohrCoulomb::is_elastic(const Strength              &strength,
                            const std::array<double, 3> &s) const
    {
      // The planes and tolerance of make_surfaces() and
      // return_principal_inline(), computed in the same order, so that the
      // answer is the return's to the last bit.
      const double sin_phi = std::sin(strength.friction_angle);
      const double k = 2 * strength.cohesion * std::cos(strength.friction_angle);
      const double tension_cutoff = strength.tension_cutoff;
      const double scale          = std::max(
        {std::abs(s[0]), std::abs(s[1]), std::abs(s[2]), k, tension_cutoff});
      const double tol = yield_relative_tolerance * scale;
      const std::array<std::array<double, 3>, 3> shear{
        {{{1 + sin_phi, 0, -(1 - sin_phi)}},
         {{1 + sin_phi, -(1 - sin_phi), 0}},
         {{0, 1 + sin_phi, -(1 - sin_phi)}}}};
      for (const auto &a : shear)
        if (!(a[0] * s[0] + a[1] * s[1] + a[2] * s[2] - k <= tol))
          return false;
      for (unsigned int i = 0; i < 3; ++i)
        {
          std::array<double, 3> a{{0, 0, 0}};
          a[i] = 1;
          if (!(a[0] * s[0] + a[1] * s[1] + a[2] * s[2] - tension_cutoff <= tol))
            return false;
        }
      return true;
    }


    unsigned int
    MohrCoulomb::return_at_kappa(std::array<double, 3> &s,
                                 double                &plastic_shear_increment,
                                 const double           kappa,
                                 const double           start,
                                 const double           end) const
    {
      if (kappa >= end)
        return return_principal_inline<true>(residual, s, plastic_shear_increment);
      if (kappa <= start)
        return return_principal_inline<true>(peak, s, plastic_shear_increment);
      return return_principal_inline<false>(
        make_surfaces(strength_at(kappa, start, end), false),
        s,
        plastic_shear_increment);
    }


    unsigned int
    MohrCoulomb::return_with_softening(std::array<double, 3> &s,
                                       double &plastic_shear_increment,
                                       const double kappa,
                                       const double kappa_scale,
                                       const bool   fixed_strength) const
    {
      // The softening range of this point (scaled by the cell size, or as
      // given: kappa_scale = 1 divides exactly).
      const double softening_start = this->softening_start / kappa_scale;
      const double softening_end   = this->softening_end / kappa_scale;
      if (kappa >= softening_end)
        return return_principal_inline<true>(residual, s, plastic_shear_increment);

      const std::array<double, 3> trial = s;
      // The return from the trial stress with the strength at k.
      double     increment = 0;
      const auto return_at = [&](const double k) {
        s = trial;
        return return_at_kappa(s, increment, k, softening_start, softening_end);
      };

      // Most steps of a point inside the softening range are elastic: the
      // elastic check of the return at the strength of kappa, without
      // building that strength's surfaces (their return directions and
      // plastic strain factors were most of a softening update's cost).
      if (kappa > softening_start && is_elastic(strength_at(kappa, softening_start, softening_end), trial))
        {
          plastic_shear_increment = 0;
          return 0;
        }

      // Elastic, plastic and still before the peak strain, or at a fixed
      // strength (non-local): done.
      unsigned int bits = return_at(kappa);
      if (fixed_strength || bits == 0 || kappa + increment <= softening_start)
        {
          plastic_shear_increment = increment;
          return bits;
        }

      // The strength at the end of the step, k = kappa + dkappa(k): a root
      // of g(k) = kappa + dkappa(k) - k. At the lower end (kappa, or the
      // peak strain for a point that crosses it) g > 0; at kappa plus the
      // increment of a return to the residual strength, the smallest
      // surface, g <= 0. Regula falsi (Illinois) on that bracket.
      double       lo   = std::max(kappa, softening_start);
      double       g_lo = kappa + increment - lo;
      return_at(softening_end);
      double hi   = kappa + increment;
      bits        = return_at(hi);
      double g_hi = kappa + increment - hi;
      // g_hi = 0: the residual strength is reached within the step. (A
      // positive g_hi, a strength path that is not monotonic, is not
      // possible with linear softening; the return at hi is then kept.)
      const double tolerance = 1e-12 * (softening_end - softening_start);
      if (g_hi < 0)
        {
          int side = 0;
          for (unsigned int it = 0; it < 100; ++it)
            {
              const double k = (lo * g_hi - hi * g_lo) / (g_hi - g_lo);
              bits           = return_at(k);
              const double g = kappa + increment - k;
              if (std::abs(g) <= tolerance || hi - lo <= tolerance)
                break;
              if (g > 0)
                {
                  lo = k, g_lo = g;
                  if (side == 1)
                    g_hi *= 0.5;
                  side = 1;
                }
              else
                {
                  hi = k, g_hi = g;
                  if (side == -1)
                    g_lo *= 0.5;
                  side = -1;
                }
            }
        }
      plastic_shear_increment = increment;
      return bits;
    }


    void
    MohrCoulomb::update_stress(const SymmetricTensor<2, 3> &strain_increment,
                               SymmetricTensor<2, 3>       &stress,
                               const ArrayView<double>     &state,
                               const double                 time_step) const
    {
      // No cell: the softening strains as given.
      MohrCoulomb::update_stress_in_cell(
        strain_increment, stress, state, time_step, 0.);
    }


    void
    MohrCoulomb::update_stress_in_cell(
      const SymmetricTensor<2, 3> &strain_increment,
      SymmetricTensor<2, 3>       &stress,
      const ArrayView<double>     &state,
      const double,
      const double cell_size) const
    {
      if (softening)
        update_stress_with_softening(
          strain_increment,
          stress,
          state,
          reference_cell_size > 0 && cell_size > 0 ?
            cell_size / reference_cell_size :
            1.);
      else
        update_stress<false>(strain_increment, stress, state, 1.);
    }


    void
    MohrCoulomb::update_stress_with_softening(
      const SymmetricTensor<2, 3> &strain_increment,
      SymmetricTensor<2, 3>       &stress,
      const ArrayView<double>     &state,
      const double                 kappa_scale) const
    {
      update_stress<true>(strain_increment, stress, state, kappa_scale);
    }


    template <bool with_softening>
    inline DEAL_II_ALWAYS_INLINE void
    MohrCoulomb::update_stress(const SymmetricTensor<2, 3> &strain_increment,
                               SymmetricTensor<2, 3>       &stress,
                               const ArrayView<double>     &state,
                               const double                 kappa_scale) const
    {
      (void)kappa_scale; // without softening
      AssertIndexRange(0, state.size());
      // The return of this point: with softening at its accumulated plastic
      // shear strain. (Without, the return never reaches a function that
      // takes the principal values by reference, so they stay in
      // registers: the softening branch in the same function cost 10 % of
      // the model's time.)
      const auto return_mapping = [&](std::array<double, 3> &s,
                                      double &plastic_shear_increment) {
        if constexpr (with_softening)
          {
            // Non-local: at the fixed strength of the regularised strain
            // (explicit in it; the class documentation).
            if (nonlocal_state)
              return return_with_softening(
                s, plastic_shear_increment, state[1], 1., true);
            return return_with_softening(s,
                                         plastic_shear_increment,
                                         state[0],
                                         kappa_scale,
                                         false);
          }
        else
          return return_principal_inline<true>(peak,
                                               s,
                                               plastic_shear_increment);
      };
      // The same elastic predictor as LinearElastic, so that an elastic
      // step gives the same stress to the last bit.
      SymmetricTensor<2, 3> trial = stress;
      elasticity.add_stress_increment(strain_increment, trial);

      std::array<double, 3> s;
      if (trial[0][2] == 0 && trial[1][2] == 0)
        {
          // Plane strain (every 2D run): z is a principal direction and the
          // in-plane pair has the closed form of a symmetric 2x2 matrix,
          // centre c +- radius r of Mohr's circle. Unlike the trigonometric
          // closed form of a 3x3 matrix it keeps its digits when two values
          // coincide (r -> 0), and it costs a square root instead of an
          // iterative decomposition: the stress update was two thirds of
          // the flume's run time.
          //
          // The values are kept in named scalars and the three orderings
          // written out: sorting through an index array makes the compiler
          // store the values one by one and load them back as a pair, a
          // store-forwarding stall measured at a sixth of this function's
          // time.
          const double sxy   = trial[0][1];
          const double szz   = trial[2][2];
          const double c     = 0.5 * (trial[0][0] + trial[1][1]);
          const double h     = 0.5 * (trial[0][0] - trial[1][1]);
          const double r     = std::sqrt(h * h + sxy * sxy);
          const double major = c + r;
          const double minor = c - r;
          // Where s_zz falls in the descending order: 0 first, 1 between
          // the in-plane pair, 2 last.
          const unsigned int z_position =
            szz > major ? 0 : (szz > minor ? 1 : 2);
          if (z_position == 0)
            s = {{szz, major, minor}};
          else if (z_position == 1)
            s = {{major, szz, minor}};
          else
            s = {{major, minor, szz}};
          double plastic_shear_increment;
          if (return_mapping(s, plastic_shear_increment) == 0)
            {
              stress = trial;
              return;
            }
          state[0] += plastic_shear_increment;
          const double new_zz    = s[z_position];
          const double new_major = s[z_position == 0 ? 1 : 0];
          const double new_minor = s[z_position == 2 ? 1 : 2];
          // The returned stress is coaxial with the trial stress: with
          // the direction (cos a, sin a) of the larger in-plane value,
          // cos 2a = h / r and sin 2a = sigma_xy / r, so no angle is
          // needed. (r = 0: every in-plane direction is principal.)
          const double cos_2a = r > 0 ? h / r : 1.;
          const double sin_2a = r > 0 ? sxy / r : 0.;
          const double centre = 0.5 * (new_major + new_minor);
          const double radius = 0.5 * (new_major - new_minor);
          stress              = 0;
          stress[0][0]        = centre + radius * cos_2a;
          stress[1][1]        = centre - radius * cos_2a;
          stress[0][1]        = radius * sin_2a;
          stress[2][2]        = new_zz;
          return;
        }

      // General 3D stress. A point that is elastic by a margin (most
      // points of a body at rest or in elastic motion) needs no principal
      // stresses: with p the mean stress and J2 the second invariant of
      // the deviator, sigma_1 - sigma_3 <= 2 sqrt(J2), sigma_1 + sigma_3 <=
      // 2 p + sqrt(J2 / 3) and sigma_1 <= p + 2 sqrt(J2 / 3), so if these
      // bounds leave the Mohr-Coulomb plane and the tension cutoff below
      // zero by more than round-off, every surface is (the same answer,
      // stress = trial, as the test on the principal values below, whose
      // decomposition costs more than the rest of a 3D update).
      if constexpr (!with_softening)
        {
          const double p  = (trial[0][0] + trial[1][1] + trial[2][2]) / 3.;
          const double dx = trial[0][0] - p, dy = trial[1][1] - p,
                       dz = trial[2][2] - p;
          const double J2 = 0.5 * (dx * dx + dy * dy + dz * dz) +
                            trial[0][1] * trial[0][1] +
                            trial[0][2] * trial[0][2] +
                            trial[1][2] * trial[1][2];
          const double root_J2      = std::sqrt(J2);
          const double root_J2_by_3 = std::sqrt(J2 / 3.);
          const double sin_phi      = peak.gradient[0][0] - 1.;
          const double k            = peak.bound[0];
          const double t            = peak.bound[3];
          const double margin =
            1e-10 * (std::abs(p) + root_J2 + std::abs(k) + std::abs(t));
          if (2. * root_J2 + sin_phi * (2. * p + root_J2_by_3) - k < -margin &&
              p + 2. * root_J2_by_3 - t < -margin)
            {
              stress = trial;
              return;
            }
        }
      // Principal values to full accuracy also where two coincide, as the
      // edge returns put them (principal_stresses.h). Without softening in
      // two stages: first approximate values, then, if needed, the
      // accurate values and the directions.
      std::array<std::pair<double, Tensor<1, 3>>, 3> principal;
      if constexpr (with_softening)
        principal = principal_values_and_directions(trial);
      else
        {
          // Inside every surface by more than the approximate values'
          // error bound (a hundred times their worst error): then the
          // accurate values would find the point elastic too (f_k <= 0,
          // within the return's tolerance), and the directions are not
          // needed. In the 3D block on a floor (scripts/throughput_3d.sh)
          // this settles a third of all updates, points near a surface
          // but inside it; a yielding point pays one square root and the
          // six plane values more.
          const PrincipalStresses principal_stresses(trial);
          const auto  &values = principal_stresses.approximate_values();
          const double error  = principal_stresses.error_bound();
          bool         inside = true;
          for (unsigned int k = 0; k < 6; ++k)
            {
              const auto &a = peak.gradient[k];
              inside =
                inside &&
                peak.plane_value(k, values) +
                    (std::abs(a[0]) + std::abs(a[1]) + std::abs(a[2])) * error <
                  0.;
            }
          if (inside)
            {
              stress = trial;
              return;
            }
          principal = principal_stresses.values_and_directions();
        }
      s = {{principal[0].first, principal[1].first, principal[2].first}};

      double plastic_shear_increment;
      if (return_mapping(s, plastic_shear_increment) == 0)
      {
        stress = trial;
        return;
      }

      // sum_i s_i v_i v_i^T, the returned stress (coaxial with the trial).
      for (unsigned int a = 0; a < 3; ++a)
        for (unsigned int b = a; b < 3; ++b)
          stress[a][b] =
            s[0] * principal[0].second[a] * principal[0].second[b] +
            s[1] * principal[1].second[a] * principal[1].second[b] +
            s[2] * principal[2].second[a] * principal[2].second[b];
      state[0] += plastic_shear_increment;
    }


    double
    MohrCoulomb::strain_energy_density(
      const SymmetricTensor<2, 3> &stress) const
    {
      return elasticity.strain_energy_density(stress);
    }


    double
    MohrCoulomb::p_wave_modulus() const
    {
      return elasticity.p_wave_modulus();
    }
  } // namespace MaterialModels
} // namespace MPM

MPM_REGISTER_MATERIAL_MODEL(
  MPM::MaterialModels::MohrCoulomb,
  "mohr coulomb",
  "Elastic - perfectly plastic Mohr-Coulomb with tension cutoff and "
  "non-associated flow (plane strain in 2D).")

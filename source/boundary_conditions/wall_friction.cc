#include <mpm/boundary_conditions/wall_friction.h>

#include <algorithm>

namespace MPM
{
  namespace WallFriction
  {
    template <int dim>
    Tensor<1, dim>
    frictional_acceleration(const Tensor<1, dim>        &v,
                            const Tensor<1, dim>        &a,
                            const Tensor<1, dim>        &n,
                            const BasalLaw<dim>         &law,
                            const WallNodeGeometry      &geometry,
                            const double                 dt,
                            bool *const                  sticks,
                            const bool                   held,
                            const std::optional<double> &effective_reaction)
    {
      if (sticks != nullptr)
        *sticks = false;
      // Normal velocity change per unit time that the wall must remove to
      // keep v_n = 0 at the end of the step: the normal reaction per unit
      // mass. The wall only pushes, so it resists only if it is positive.
      const double v_n      = v * n;
      const double a_n      = a * n;
      const double reaction = normal_reaction(v, a, n, dt);
      if (reaction <= 0)
        {
          if (!held || !law.rate_dependent())
            return a;
          // Held on the wall by the last update: the drag alone, on the
          // trial tangential velocity.
          const Tensor<1, dim> v_t       = v - v_n * n;
          const Tensor<1, dim> v_t_trial = v_t + dt * (a - a_n * n);
          const double         speed     = v_t_trial.norm();
          if (speed == 0)
            return a;
          const Tensor<1, dim> v_t_new =
            (law.sliding_speed(speed, dt, geometry) / speed) * v_t_trial;
          return a_n * n + (v_t_new - v_t) / dt;
        }

      // Coulomb's law integrated by backward Euler: the tangential
      // velocity the node would reach without friction (the trial
      // velocity) is reduced by at most mu * reaction * dt. If that stops
      // it, the node sticks (static friction, or kinetic friction that
      // would otherwise reverse the motion within the step); else it
      // slides on with friction opposing the trial velocity, and the
      // law's rate-dependent part slows it further.
      const Tensor<1, dim> v_t       = v - v_n * n;
      const Tensor<1, dim> v_t_trial = v_t + dt * (a - a_n * n);
      const double         speed     = v_t_trial.norm();
      // The rate-independent resistance takes the effective normal
      // reaction where the caller gives one (the wall's push less what the
      // pore water carries; a remembered normal force).
      const double capacity =
        law.static_capacity(effective_reaction.value_or(reaction), dt);
      Tensor<1, dim>       v_t_new =
        speed <= capacity ? Tensor<1, dim>() :
                            (1. - capacity / speed) * v_t_trial;
      if (sticks != nullptr)
        *sticks = speed <= capacity;
      if (law.rate_dependent() && speed > capacity)
        {
          const double sliding = v_t_new.norm();
          if (sliding > 0)
            v_t_new *= law.sliding_speed(sliding, dt, geometry) / sliding;
        }
      return a_n * n + (v_t_new - v_t) / dt;
    }


    template <int dim>
    Tensor<1, dim>
    edge_frictional_acceleration(
      const Tensor<1, dim>                       &v,
      const Tensor<1, dim>                       &a,
      const std::array<Tensor<1, dim>, 2>        &n,
      const std::array<const BasalLaw<dim> *, 2> &laws,
      const std::array<WallNodeGeometry, 2>      &geometry,
      const double                                dt,
      bool *const                                 sticks,
      const std::array<double, 2>                &relief,
      const std::array<double, 2>                *effective_impulses)
    {
      if (sticks != nullptr)
        *sticks = false;
      // Wall impulses lambda_j n_j that bring w onto the edge:
      // G lambda = -N w with the Gram matrix G of the normals.
      const auto impulses = edge_wall_impulses(v, a, n, dt);
      if (!impulses)
        return a;
      const Tensor<1, dim>        w      = v + dt * a;
      const double                g01    = n[0] * n[1];
      const double                det    = 1 - g01 * g01;
      const std::array<double, 2> lambda = {{-(*impulses)[0], -(*impulses)[1]}};
      double capacity      = 0;
      bool   rate_dependent = false;
      for (unsigned int j = 0; j < 2; ++j)
        if (laws[j] != nullptr)
          {
            // The rate-independent resistance of wall j takes its
            // effective normal impulse: the wall's less what the pore
            // water carries (relief per unit mass and time, as in
            // frictional_acceleration()).
            capacity +=
              laws[j]->static_capacity(effective_impulses != nullptr ?
                                         (*effective_impulses)[j] :
                                         std::max(0.,
                                                  -lambda[j] - dt * relief[j]),
                                       1.);
            rate_dependent |= laws[j]->rate_dependent() && lambda[j] < 0;
          }
      if (capacity <= 0 && !rate_dependent)
        return a;
      // Components along the edge (the free direction) and across it.
      const auto along = [&](const Tensor<1, dim> &u) {
        return along_edge(u, n, det);
      };
      const Tensor<1, dim> w_t   = along(w);
      const double         speed = w_t.norm();
      Tensor<1, dim>       w_t_new =
        speed <= capacity ? Tensor<1, dim>() : (1. - capacity / speed) * w_t;
      if (sticks != nullptr)
        *sticks = speed <= capacity;
      if (rate_dependent && speed > capacity)
        for (unsigned int j = 0; j < 2; ++j)
          if (laws[j] != nullptr && laws[j]->rate_dependent() && lambda[j] < 0)
            {
              const double sliding = w_t_new.norm();
              if (sliding > 0)
                w_t_new *=
                  laws[j]->sliding_speed(sliding, dt, geometry[j]) / sliding;
            }
      return (a - along(a)) + (w_t_new - along(v)) / dt;
    }


    template Tensor<1, 2>
    frictional_acceleration(const Tensor<1, 2> &,
                            const Tensor<1, 2> &,
                            const Tensor<1, 2> &,
                            const BasalLaw<2> &,
                            const WallNodeGeometry &,
                            const double,
                            bool *const,
                            const bool,
                            const std::optional<double> &);
    template Tensor<1, 3>
    frictional_acceleration(const Tensor<1, 3> &,
                            const Tensor<1, 3> &,
                            const Tensor<1, 3> &,
                            const BasalLaw<3> &,
                            const WallNodeGeometry &,
                            const double,
                            bool *const,
                            const bool,
                            const std::optional<double> &);
    template Tensor<1, 2>
    edge_frictional_acceleration(const Tensor<1, 2> &,
                                 const Tensor<1, 2> &,
                                 const std::array<Tensor<1, 2>, 2> &,
                                 const std::array<const BasalLaw<2> *, 2> &,
                                 const std::array<WallNodeGeometry, 2> &,
                                 const double,
                                 bool *const,
                                 const std::array<double, 2> &,
                                 const std::array<double, 2> *);
    template Tensor<1, 3>
    edge_frictional_acceleration(const Tensor<1, 3> &,
                                 const Tensor<1, 3> &,
                                 const std::array<Tensor<1, 3>, 2> &,
                                 const std::array<const BasalLaw<3> *, 2> &,
                                 const std::array<WallNodeGeometry, 2> &,
                                 const double,
                                 bool *const,
                                 const std::array<double, 2> &,
                                 const std::array<double, 2> *);
  } // namespace WallFriction
} // namespace MPM

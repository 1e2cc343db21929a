#ifndef mpm_grid_nodal_vector_h
#define mpm_grid_nodal_vector_h

#include <deal.II/base/partitioner.h>

#include <deal.II/lac/la_parallel_vector.h>

#include <memory>
#include <utility>
#include <vector>

namespace MPM
{
  /**
   * The vector type of every nodal field (mass, momentum, force, velocity).
   * deal.II's own distributed vector: its local elements are contiguous
   * (owned entries first, then ghosts), so the hot loops index it with
   * precomputed local indices, and compress(add) sums the contributions
   * of neighbouring ranks to shared nodes.
   */
  using NodalVector = dealii::LinearAlgebra::distributed::Vector<double>;

  /**
   * The nodal fields of one explicit step: what particle-to-grid writes
   * (mass, momentum, force), what the nodal update makes of them
   * (velocity at the start of the step, end-of-step velocity, and the
   * acceleration consistent with the constrained velocity change), and
   * what grid-to-particle reads. Mass is lumped and stored in each
   * component's entry.
   *
   * It is also the list of every nodal vector of the step: a component
   * with fields of its own (XPIC's iterates, a second phase's momentum)
   * adds them with add(), and they follow the partition (reinit()) and
   * are zeroed with the step's fields (zero()) without any other code
   * knowing them.
   */
  class NodalFields
  {
  public:
    /// How a field's ghost entries become valid.
    enum class Ghosts
    {
      /// Summed over ranks (compress(add), then update_ghost_values())
      /// by the pass that writes it.
      summed,
      /// Computed by every rank for all nodes its points touch, ghosts
      /// included, from summed fields: valid without an exchange.
      computed
    };

    NodalFields()
    {
      add(mass, Ghosts::summed);
      add(momentum, Ghosts::summed);
      add(force, Ghosts::summed);
      add(velocity, Ghosts::computed);
      add(velocity_new, Ghosts::computed);
      add(acceleration, Ghosts::computed);
    }

    // The list holds pointers to the members: neither copied nor moved.
    NodalFields(const NodalFields &) = delete;
    NodalFields &
    operator=(const NodalFields &) = delete;

    NodalVector mass;
    NodalVector momentum;
    NodalVector force;
    /// Constrained nodal velocity at the start of the step.
    NodalVector velocity;
    /// Constrained nodal velocity at the end of the step.
    NodalVector velocity_new;
    NodalVector acceleration;

    /// Add @p field (owned by the caller, who outlives this object).
    void
    add(NodalVector &field, const Ghosts ghosts)
    {
      fields.emplace_back(&field, ghosts);
    }

    /// Every field on the layout @p partitioner (zero, ghosts valid for
    /// the computed ones).
    void
    reinit(
      const std::shared_ptr<const dealii::Utilities::MPI::Partitioner>
        &partitioner)
    {
      for (auto &[field, ghosts] : fields)
        field->reinit(partitioner);
      mark_computed_ghosts();
    }

    /**
     * Zero every field with @p zero (a function void(NodalVector &) that
     * zeroes the entries the previous step touched) and mark the computed
     * fields' ghosts valid.
     */
    template <typename Zero>
    void
    zero(const Zero &zero)
    {
      for (auto &[field, ghosts] : fields)
        zero(*field);
      mark_computed_ghosts();
    }

  private:
    void
    mark_computed_ghosts()
    {
      for (auto &[field, ghosts] : fields)
        if (ghosts == Ghosts::computed)
          field->set_ghost_state(true);
    }

    std::vector<std::pair<NodalVector *, Ghosts>> fields;
  };
} // namespace MPM

#endif

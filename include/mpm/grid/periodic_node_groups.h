#ifndef mpm_grid_periodic_node_groups_h
#define mpm_grid_periodic_node_groups_h

#include <deal.II/base/exceptions.h>
#include <deal.II/base/partitioner.h>

#include <mpm/base/input_error.h>
#include <mpm/grid/nodal_vector.h>

#include <algorithm>
#include <string>
#include <vector>

namespace MPM
{
  using namespace dealii;

  /**
   * The nodal entries that periodic boundaries make one node
   * (PeriodicBoundaries::node_groups()), as local indices of the nodal
   * vectors. A particle-to-grid sum is complete when each group's entries
   * all hold the group's sum: then the two (or four, ...) copies of a
   * periodic node have the same mass, momentum and force, and every later
   * step (the nodal update, the boundary conditions, grid to particle)
   * gives them the same values without knowing about periodicity.
   *
   * The sum runs over a group's entries in ascending global index, on
   * every rank that sees the group: every rank that holds a copy
   * computes the same bits.
   */
  class PeriodicNodeGroups
  {
  public:
    /**
     * Take the groups @p global_groups (global indices) into the local
     * numbering of @p partitioner. Only the groups wholly known to the
     * rank (owned or ghost entries) are summed here: periodicity in the
     * p4est forest makes the cells across a periodic boundary ghosts, so
     * every node of a locally owned cell is in such a group.
     */
    void
    reinit(const std::vector<std::vector<types::global_dof_index>> &global_groups,
           const Utilities::MPI::Partitioner                       &partitioner)
    {
      members.clear();
      first_member.assign(1, 0);
      group_of_entry.assign(partitioner.locally_owned_size() +
                              partitioner.n_ghost_indices(),
                            none);
      for (const auto &group : global_groups)
        {
          const bool known =
            std::all_of(group.begin(), group.end(), [&](const auto i) {
              return partitioner.in_local_range(i) ||
                     partitioner.is_ghost_entry(i);
            });
          if (!known)
            {
              // A node of a ghost cell only: this rank's points do not
              // reach it unless a weight function's support crosses
              // more than one cell (for_each_copy() stops then).
              for (const auto i : group)
                if (partitioner.in_local_range(i) ||
                    partitioner.is_ghost_entry(i))
                  group_of_entry[partitioner.global_to_local(i)] = incomplete;
              continue;
            }
          for (const auto i : group)
            {
              const unsigned int local = partitioner.global_to_local(i);
              group_of_entry[local]    = first_member.size() - 1;
              members.push_back(local);
            }
          first_member.push_back(members.size());
        }
    }

    bool
    empty() const
    {
      return members.empty();
    }

    /// Give every entry of each group of @p v the group's sum.
    void
    sum(NodalVector &v) const
    {
      for (unsigned int g = 0; g + 1 < first_member.size(); ++g)
        {
          double s = 0;
          for (unsigned int k = first_member[g]; k < first_member[g + 1]; ++k)
            s += v.local_element(members[k]);
          for (unsigned int k = first_member[g]; k < first_member[g + 1]; ++k)
            v.local_element(members[k]) = s;
        }
    }

    /**
     * Call @p f(j) for every other entry j of the group of the local entry
     * @p i (nothing if @p i is in no group).
     */
    template <typename Function>
    void
    for_each_copy(const unsigned int i, const Function &f) const
    {
      if (group_of_entry.empty() || group_of_entry[i] == none)
        return;
      if (group_of_entry[i] == incomplete)
        throw InputError(
          "Mesh/Periodic boundaries: the material points of one rank reach "
          "a periodic node whose copies that rank does not see (a weight "
          "function's support wider than one cell beyond the rank's "
          "cells); run on fewer ranks.");
      const unsigned int g = group_of_entry[i];
      for (unsigned int k = first_member[g]; k < first_member[g + 1]; ++k)
        if (members[k] != i)
          f(members[k]);
    }

    /**
     * Whether the local entry @p i has a copy of lower global index in
     * @p partitioner's numbering (its group's other entries): of a
     * periodic node's copies, all but one. False outside a group and in a
     * group this rank does not see whole.
     */
    bool
    is_later_copy(const unsigned int                 i,
                  const Utilities::MPI::Partitioner &partitioner) const
    {
      if (group_of_entry.empty() || group_of_entry[i] == none ||
          group_of_entry[i] == incomplete)
        return false;
      const unsigned int g = group_of_entry[i];
      for (unsigned int k = first_member[g]; k < first_member[g + 1]; ++k)
        if (partitioner.local_to_global(members[k]) <
            partitioner.local_to_global(i))
          return true;
      return false;
    }

  private:
    static constexpr unsigned int none       = numbers::invalid_unsigned_int;
    static constexpr unsigned int incomplete = none - 1;
    /// The local entries of all groups, group after group.
    std::vector<unsigned int> members;
    /// Where each group starts in members (and one past the last).
    std::vector<unsigned int> first_member{0};
    /// Per local entry: its group, or none.
    std::vector<unsigned int> group_of_entry;
  };
} // namespace MPM

#endif

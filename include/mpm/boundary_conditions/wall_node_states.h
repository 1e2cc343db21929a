#ifndef mpm_boundary_conditions_wall_node_states_h
#define mpm_boundary_conditions_wall_node_states_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/point.h>

#include <boost/serialization/vector.hpp>

#include <algorithm>
#include <array>
#include <vector>

namespace MPM
{
  using namespace dealii;

  /**
   * What the frictional walls' nodes carry from one step to the next, by
   * the nodes' locations: whether the last nodal update held a node on its
   * wall (and whether it slid or stuck there), and the normal force it
   * remembers (NormalStressMemory). By location, not by index, because a
   * new setup() after repartitioning may put a node on another rank, and
   * because a checkpoint is resumed on any number of ranks: the states of
   * all ranks are gathered into one list (gather()) and every rank picks
   * its nodes from it (find()), so that a resumed or repartitioned run
   * continues bit for bit.
   */
  template <int dim>
  class WallNodeStates
  {
  public:
    /// How the last nodal update left a node.
    enum class Contact : unsigned char
    {
      free,
      sliding,
      stuck
    };

    /// One node's state; a node may be listed by several ranks (a ghost).
    struct Record
    {
      Point<dim> location;
      Contact    contact = Contact::free;
      /// The remembered normal force (N); negative: none. At a 3D edge
      /// node, its first wall's.
      double remembered_normal_force = -1;
      /// At a 3D edge node, the normal force its second wall remembers
      /// (N); negative: none.
      double remembered_edge_force = -1;

      template <class Archive>
      void
      serialize(Archive &ar, const unsigned int)
      {
        ar &location &contact &remembered_normal_force &remembered_edge_force;
      }
    };

    void
    add(const Point<dim> &location,
        const Contact     contact,
        const double      remembered_normal_force,
        const double      remembered_edge_force = -1)
    {
      records.push_back(
        {location, contact, remembered_normal_force, remembered_edge_force});
      sorted = false;
    }

    /// The records of every rank of @p comm, on every rank, sorted.
    static WallNodeStates
    gather(const MPI_Comm comm, const WallNodeStates &local)
    {
      WallNodeStates all;
      for (const auto &r : Utilities::MPI::all_gather(comm, local))
        all.records.insert(all.records.end(),
                           r.records.begin(),
                           r.records.end());
      all.sort();
      return all;
    }

    /**
     * The state at @p location, the exact location of a mesh vertex
     * (sort() first): of all records there, the firmest contact (stuck,
     * then sliding) and a remembered force if one is remembered.
     */
    Record
    find(const Point<dim> &location) const
    {
      Assert(sorted, ExcMessage("WallNodeStates::sort() first."));
      Record state;
      state.location = location;
      const auto range =
        std::equal_range(records.begin(), records.end(), state, location_less);
      for (auto r = range.first; r != range.second; ++r)
        {
          state.contact = std::max(state.contact, r->contact);
          if (state.remembered_normal_force < 0)
            state.remembered_normal_force = r->remembered_normal_force;
          if (state.remembered_edge_force < 0)
            state.remembered_edge_force = r->remembered_edge_force;
        }
      return state;
    }

    void
    sort()
    {
      std::sort(records.begin(), records.end(), location_less);
      sorted = true;
    }

    /**
     * The checkpoint's fields (format 3: the locations of the nodes that
     * slid and of those that stuck; format 8: the remembered forces by
     * location; format 9: those of the 3D edge nodes' second walls), and
     * the states from them (older checkpoints lack the later fields:
     * empty lists).
     */
    std::array<std::vector<Point<dim>>, 2>
    contact_lists() const
    {
      std::array<std::vector<Point<dim>>, 2> lists;
      for (const auto &r : records)
        if (r.contact != Contact::free)
          lists[r.contact == Contact::stuck].push_back(r.location);
      return lists;
    }

    /// The remembered forces (format 8) and those of the 3D edge nodes'
    /// second walls (format 9), each with its nodes' locations.
    std::pair<std::vector<Point<dim>>, std::vector<double>>
    remembered_lists() const
    {
      return lists_of(&Record::remembered_normal_force);
    }

    std::pair<std::vector<Point<dim>>, std::vector<double>>
    remembered_edge_lists() const
    {
      return lists_of(&Record::remembered_edge_force);
    }

    static WallNodeStates
    from_lists(const std::array<std::vector<Point<dim>>, 2> &contact,
               const std::vector<Point<dim>>                &locations,
               const std::vector<double>                    &forces,
               const std::vector<Point<dim>> &edge_locations = {},
               const std::vector<double>     &edge_forces    = {})
    {
      WallNodeStates states;
      for (unsigned int i = 0; i < 2; ++i)
        for (const auto &x : contact[i])
          states.add(x, i == 1 ? Contact::stuck : Contact::sliding, -1);
      for (unsigned int i = 0; i < locations.size(); ++i)
        states.add(locations[i], Contact::free, forces[i]);
      for (unsigned int i = 0; i < edge_locations.size(); ++i)
        states.add(edge_locations[i], Contact::free, -1, edge_forces[i]);
      states.sort();
      return states;
    }

    template <class Archive>
    void
    serialize(Archive &ar, const unsigned int)
    {
      ar &records;
      // Records read back keep the order they were written in.
      if constexpr (Archive::is_loading::value)
        sorted = false;
    }

  private:
    /// The records that remember a force in @p field: their locations
    /// and those forces.
    std::pair<std::vector<Point<dim>>, std::vector<double>>
    lists_of(double Record::*field) const
    {
      std::pair<std::vector<Point<dim>>, std::vector<double>> lists;
      for (const auto &r : records)
        if (r.*field >= 0)
          {
            lists.first.push_back(r.location);
            lists.second.push_back(r.*field);
          }
      return lists;
    }

    /// Exact order: the locations are vertices of the same mesh.
    static bool
    location_less(const Record &a, const Record &b)
    {
      return std::lexicographical_compare(a.location.begin_raw(),
                                          a.location.end_raw(),
                                          b.location.begin_raw(),
                                          b.location.end_raw());
    }

    std::vector<Record> records;
    bool                sorted = true;
  };
} // namespace MPM

#endif

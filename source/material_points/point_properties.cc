#include <deal.II/base/exceptions.h>

#include <mpm/material_points/point_properties.h>

#include <algorithm>

namespace MPM
{
  void
  PointProperties::reset(const std::vector<std::string> &fixed_names)
  {
    names_of_slots = fixed_names;
    owners.assign(1, "fixed");
  }


  unsigned int
  PointProperties::add(const std::string              &owner,
                       const std::vector<std::string> &slot_names)
  {
    AssertThrow(std::find(owners.begin(), owners.end(), owner) == owners.end(),
                dealii::ExcMessage("The point properties of '" + owner +
                                   "' were added twice."));
    const unsigned int first = n_slots();
    owners.push_back(owner);
    names_of_slots.insert(names_of_slots.end(),
                          slot_names.begin(),
                          slot_names.end());
    return first;
  }
} // namespace MPM

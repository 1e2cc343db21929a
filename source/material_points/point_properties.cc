#include <deal.II/base/exceptions.h>

#include <mpm/material_points/point_properties.h>

#include <algorithm>

namespace MPM
{
  void
  PointProperties::reset(const std::vector<std::string> &fixed_names)
  {
    names_of_slots = fixed_names;
    blocks.assign(1, {"fixed", 0});
  }


  unsigned int
  PointProperties::add(const std::string              &owner,
                       const std::vector<std::string> &slot_names)
  {
    AssertThrow(std::none_of(blocks.begin(),
                             blocks.end(),
                             [&](const auto &b) { return b.first == owner; }),
                dealii::ExcMessage("The point properties of '" + owner +
                                   "' were added twice."));
    const unsigned int first = n_slots();
    blocks.emplace_back(owner, first);
    names_of_slots.insert(names_of_slots.end(),
                          slot_names.begin(),
                          slot_names.end());
    return first;
  }


  unsigned int
  PointProperties::first_slot(const std::string &owner) const
  {
    for (const auto &[name, first] : blocks)
      if (name == owner)
        return first;
    AssertThrow(false,
                dealii::ExcMessage("No point properties of '" + owner + "'."));
    return 0;
  }
} // namespace MPM

#ifndef mpm_material_points_point_properties_h
#define mpm_material_points_point_properties_h

#include <string>
#include <vector>

namespace MPM
{
  /**
   * The slots of a material point's property array (the doubles
   * Particles::ParticleHandler stores per point), handed out by name, as
   * ASPECT's particle property manager does: the fixed slots of
   * PropertyLayout first (mass, volume, velocity, stress, strain, material
   * id, at compile-time positions the hot loops use), then every component
   * that keeps data on the points asks for a block at set-up (add()) and
   * keeps the first slot it got: the materials' state variables, the
   * transfer scheme's (APIC's C_p), the weights' (CPDI's domain), and
   * whatever a new component needs (a second phase's velocity and pore
   * pressure). Each slot has the name the output files give it.
   */
  class PointProperties
  {
  public:
    /// Start again with the fixed slots, named @p fixed_names.
    void
    reset(const std::vector<std::string> &fixed_names);

    /**
     * A block of slots for @p owner, one per name in @p slot_names (a
     * vector or tensor repeats its name, as the VTU writer groups them);
     * returns the block's first slot, where the owner keeps its data. An
     * owner asks once.
     */
    unsigned int
    add(const std::string &owner, const std::vector<std::string> &slot_names);

    /// How many slots a point has.
    unsigned int
    n_slots() const
    {
      return names_of_slots.size();
    }

    /// The name of every slot, in order: the output files' field names.
    const std::vector<std::string> &
    names() const
    {
      return names_of_slots;
    }

  private:
    std::vector<std::string> names_of_slots;
    /// The owners of the blocks, in the order they were added.
    std::vector<std::string> owners;
  };
} // namespace MPM

#endif

#ifndef mpm_postprocess_volume_quantiles_h
#define mpm_postprocess_volume_quantiles_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/utilities.h>

#include <string>
#include <vector>

namespace MPM
{
  namespace Postprocessors
  {
    using namespace dealii;

    /**
     * The volume quantiles of a final deposit ('Runout volume fractions'),
     * which the postprocessors that bin a deposit (column collapse, flume)
     * report beside its front: cumulative measures that a thin tail or a
     * few points thrown ahead do not move by a bin. The parameter is
     * declared with the postprocessor's own @p description of where the
     * sum starts.
     */
    inline void
    declare_volume_fractions(ParameterHandler  &prm,
                             const std::string &description)
    {
      prm.declare_entry("Runout volume fractions",
                        "0.95, 0.99",
                        Patterns::List(Patterns::Double(0, 1)),
                        description);
    }

    inline std::vector<double>
    parse_volume_fractions(const ParameterHandler &prm)
    {
      std::vector<double> fractions;
      for (const auto &q :
           Utilities::split_string_list(prm.get("Runout volume fractions")))
        fractions.push_back(Utilities::string_to_double(q));
      return fractions;
    }

    /**
     * Where the sum of @p volume_in_bin (one value per bin, the first bin
     * numbered @p first_bin) reaches the share @p q of @p total, in bins:
     * b + f for the bin b where it does, f interpolated linearly in that
     * bin; first_bin + the number of bins if it never does. Times the bin
     * width, the quantile's position.
     */
    inline double
    volume_quantile_in_bins(const std::vector<double> &volume_in_bin,
                            const double               total,
                            const double               q,
                            const long                 first_bin = 0)
    {
      const long n_bins = volume_in_bin.size();
      double     below  = 0;
      for (long b = 0; b < n_bins; ++b)
        {
          const double in_bin = volume_in_bin[b];
          if (in_bin > 0 && below + in_bin >= q * total)
            return (first_bin + b) + (q * total - below) / in_bin;
          below += in_bin;
        }
      return first_bin + n_bins;
    }
  } // namespace Postprocessors
} // namespace MPM

#endif

// Summaries of weighted samples (a value per surface sample, weighted by the area it stands for):
// the statistics and histograms the evaluation report prints.
#pragma once

#include <cstddef>
#include <vector>

namespace jawmesh {

/// Summary of weighted values. Percentiles are weighted: p_q is the smallest value whose
/// cumulative weight (values sorted ascending) reaches q * total weight.
/// min and max run over every value, including those of weight 0 (extremes found by refinement).
struct Distribution {
    std::size_t count = 0;     ///< values, including weight-0 ones
    double totalWeight = 0;    ///< e.g. mm^2 of surface
    double min = 0, p05 = 0, median = 0, p95 = 0, mean = 0, max = 0;  ///< 0 when count == 0
};

/// Summarises values[i] with weights[i] (same size, weights >= 0). The mean is the weighted mean
/// (of the positive-weight values). Values must not be NaN. Deterministic. Cost: O(n log n).
Distribution summarizeWeighted(const std::vector<double>& values, const std::vector<double>& weights);

/// summarizeWeighted() with every weight 1, in O(n) (selection instead of a sort): for the
/// per-tet quality measures of a million-tet mesh. Same results as with explicit unit weights.
Distribution summarizeUnweighted(std::vector<double> values);

/// Weighted percentile q in [0, 1] of values, with the definition above (0 when there is no weight).
double weightedPercentile(const std::vector<double>& values, const std::vector<double>& weights, double q);

/// Weight falling in each of `bins` equal bins over [lo, hi); values outside go to the first or
/// last bin (so the histogram keeps all the weight). bins >= 1, hi > lo. Cost: O(n).
std::vector<double> weightedHistogram(const std::vector<double>& values, const std::vector<double>& weights, double lo,
                                      double hi, int bins);

}  // namespace jawmesh

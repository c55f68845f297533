// Implements filters/WeightedDistribution.h; what it computes, its rules and its contract are documented there.
#include "filters/WeightedDistribution.h"

#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>

namespace jawmesh {
namespace {

/// (value, weight) pairs sorted by value. Equal values are interchangeable for a percentile (it
/// returns a value), so the order among ties does not matter; sorting pairs keeps it unique anyway
/// (and the same in parallel: the report's bone has millions of samples).
std::vector<std::pair<double, double>> sortedPairs(const std::vector<double>& values, const std::vector<double>& weights) {
    std::vector<std::pair<double, double>> p(values.size());
    for (std::size_t i = 0; i < values.size(); ++i) p[i] = {values[i], weights[i]};
    tbb::parallel_sort(p.begin(), p.end());
    return p;
}

double percentileOfSorted(const std::vector<std::pair<double, double>>& sorted, double total, double q) {
    if (total <= 0) return 0;
    const double target = q * total;
    double cumulative = 0;
    for (const auto& [value, weight] : sorted) {
        if (weight <= 0) continue;
        cumulative += weight;
        if (cumulative >= target) return value;
    }
    // Rounding left the sum a hair below the target: the largest weighted value.
    for (auto it = sorted.rbegin(); it != sorted.rend(); ++it)
        if (it->second > 0) return it->first;
    return 0;
}

}  // namespace

double weightedPercentile(const std::vector<double>& values, const std::vector<double>& weights, double q) {
    const double total = std::accumulate(weights.begin(), weights.end(), 0.0);
    return percentileOfSorted(sortedPairs(values, weights), total, q);
}

Distribution summarizeWeighted(const std::vector<double>& values, const std::vector<double>& weights) {
    Distribution d;
    d.count = values.size();
    if (values.empty()) return d;
    double weighted = 0;
    for (std::size_t i = 0; i < values.size(); ++i) {  // input order: the same sums every time
        d.totalWeight += weights[i];
        weighted += weights[i] * values[i];
    }
    const auto sorted = sortedPairs(values, weights);
    d.min = sorted.front().first;
    d.max = sorted.back().first;
    d.mean = d.totalWeight > 0 ? weighted / d.totalWeight : 0;
    d.p05 = percentileOfSorted(sorted, d.totalWeight, 0.05);
    d.median = percentileOfSorted(sorted, d.totalWeight, 0.5);
    d.p95 = percentileOfSorted(sorted, d.totalWeight, 0.95);
    return d;
}

Distribution summarizeUnweighted(std::vector<double> values) {
    Distribution d;
    d.count = values.size();
    if (values.empty()) return d;
    double sum = 0;
    for (double v : values) sum += v;  // input order, as in summarizeWeighted
    d.totalWeight = static_cast<double>(values.size());
    d.mean = sum / d.totalWeight;
    // With unit weights the cumulative weight at sorted index i is i + 1: p_q sits at ceil(q n) - 1.
    const auto at = [&](double q) {
        const double target = q * d.totalWeight;
        const std::size_t k = static_cast<std::size_t>(std::max(1.0, std::ceil(target))) - 1;
        std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
        return values[k];
    };
    d.p05 = at(0.05);
    d.median = at(0.5);
    d.p95 = at(0.95);
    const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
    d.min = *lo;
    d.max = *hi;
    return d;
}

std::vector<double> weightedHistogram(const std::vector<double>& values, const std::vector<double>& weights, double lo,
                                      double hi, int bins) {
    std::vector<double> h(static_cast<std::size_t>(std::max(bins, 1)), 0.0);
    const double scale = static_cast<double>(h.size()) / (hi - lo);
    for (std::size_t i = 0; i < values.size(); ++i) {
        const double x = std::floor((values[i] - lo) * scale);
        const double last = static_cast<double>(h.size() - 1);
        const std::size_t bin = !(x > 0) ? 0 : x >= last ? h.size() - 1 : static_cast<std::size_t>(x);  // NaN -> 0
        h[bin] += weights[i];
    }
    return h;
}

}  // namespace jawmesh

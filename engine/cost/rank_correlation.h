// Spearman's rank correlation, for predicted versus measured task times.
#pragma once

#include <vector>

namespace aperture {

// Pearson correlation of the ranks (ties share their mean rank); 0 for fewer than 2 values.
double SpearmanCorrelation(const std::vector<double>& a, const std::vector<double>& b);

}  // namespace aperture

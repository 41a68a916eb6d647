// The minimum error boundary cut of image quilting (Efros & Freeman 2001, section 2.1):
// dynamic programming over the squared difference in an overlap strip.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

namespace shanshui::texsynth {

//! The path from the first row of `cost` (CV_64F, rows × cols, cols >= 1) to the last that
//! moves at most one column per row and has the least summed cost. Returns the column for
//! each row. Ties go to the smaller column, so the result is deterministic.
std::vector<int> minimumErrorPath(const cv::Mat& cost);

//! Summed cost along a path given as one column per row.
double pathCost(const cv::Mat& cost, const std::vector<int>& path);

}  // namespace shanshui::texsynth

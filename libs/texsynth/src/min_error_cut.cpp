#include "shanshui/texsynth/min_error_cut.h"

#include "shanshui/core/error.h"

namespace shanshui::texsynth {

std::vector<int> minimumErrorPath(const cv::Mat& cost) {
  SHANSHUI_CHECK_EQ(cost.type(), CV_64F);
  SHANSHUI_CHECK_GE(cost.rows, 1);
  SHANSHUI_CHECK_GE(cost.cols, 1);
  const int rows = cost.rows, cols = cost.cols;
  // total(r, c): least cost of a path from row 0 ending at (r, c).
  cv::Mat total(rows, cols, CV_64F);
  cost.row(0).copyTo(total.row(0));
  for (int r = 1; r < rows; ++r) {
    const double* prev = total.ptr<double>(r - 1);
    const double* here = cost.ptr<double>(r);
    double* out = total.ptr<double>(r);
    for (int c = 0; c < cols; ++c) {
      double best = prev[c];
      if (c > 0 && prev[c - 1] < best) best = prev[c - 1];
      if (c + 1 < cols && prev[c + 1] < best) best = prev[c + 1];
      out[c] = here[c] + best;
    }
  }
  std::vector<int> path(rows);
  const double* last = total.ptr<double>(rows - 1);
  int at = 0;
  for (int c = 1; c < cols; ++c) {
    if (last[c] < last[at]) at = c;
  }
  path[rows - 1] = at;
  for (int r = rows - 2; r >= 0; --r) {
    const double* prev = total.ptr<double>(r);
    int best = at;
    if (at > 0 && prev[at - 1] <= prev[best]) best = at - 1;
    if (at + 1 < cols && prev[at + 1] < prev[best]) best = at + 1;
    at = best;
    path[r] = at;
  }
  return path;
}

double pathCost(const cv::Mat& cost, const std::vector<int>& path) {
  SHANSHUI_CHECK_EQ(static_cast<int>(path.size()), cost.rows);
  double sum = 0.0;
  for (int r = 0; r < cost.rows; ++r) sum += cost.at<double>(r, path[r]);
  return sum;
}

}  // namespace shanshui::texsynth

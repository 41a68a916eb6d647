// Error-against-run-time plots for shanshui-bench: one PNG per plot, several series each,
// logarithmic axes where the values span more than a decade and are all positive.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace shanshui::bench {

struct Series {
  std::string label;
  std::vector<double> x, y;  //!< points in the order they were measured
  bool joined = true;        //!< a sweep of one knob: points joined in order; else markers only
};

struct Plot {
  std::string title, x_label, y_label;
  std::vector<Series> series;
};

//! Axis scale chosen for a set of values: logarithmic when all are positive and span more
//! than a factor of 20, linear otherwise. Non-finite values are ignored.
struct Axis {
  bool log = false;
  double lo = 0.0, hi = 1.0;   //!< the drawn range (in log10 units when log)
  std::vector<double> ticks;   //!< tick values (not logged)
  double map(double v) const;  //!< value -> [0, 1] along the axis
};
Axis chooseAxis(const std::vector<double>& values);

//! Draws the plot and writes it as PNG (atomically). Throws an Error naming the file when it
//! cannot be written; a plot without a single finite point is drawn with a "no data" note.
void writePlot(const Plot& plot, const std::filesystem::path& png);

}  // namespace shanshui::bench

// A smooth hill stored in steps, and how far a heightfield is from the hill: the oracle of
// terrain::dequantize for its test and its error-against-run-time bench.
#pragma once

#include <cmath>
#include <utility>

#include "shanshui/terrain/heightfield.h"

namespace shanshui::test {

// A Gaussian hill `height` metres high (45 cells its standard deviation) on a plain at 50 m,
// on a grid of 200 x 200 cells of 10 m.
inline double hillHeight(double height, int c, int r) {
  const double dc = c - 100.0, dr = r - 100.0;
  return 50.0 + height * std::exp(-(dc * dc + dr * dr) / (2.0 * 45.0 * 45.0));
}

// The hill with its heights rounded to whole multiples of `step` (0: not rounded).
inline terrain::Heightfield steppedHill(double height, double step) {
  terrain::Heightfield h;
  h.columns = h.rows = 200;
  h.cell_x = h.cell_y = 10.0;
  for (int r = 0; r < h.rows; ++r) {
    for (int c = 0; c < h.columns; ++c) {
      const double z = hillHeight(height, c, r);
      h.elevation.push_back(step > 0.0 ? step * std::round(z / step) : z);
    }
  }
  return h;
}

// Root mean square, over the inner samples of a hill's grid, of the height error (first)
// and of the error of the discrete Laplacian, the curvature the lines are drawn from
// (second), in metres.
inline std::pair<double, double> hillErrors(const terrain::Heightfield& h, double height) {
  double z2 = 0.0, l2 = 0.0;
  int count = 0;
  for (int r = 1; r + 1 < h.rows; ++r) {
    for (int c = 1; c + 1 < h.columns; ++c) {
      auto laplacian = [&](auto z) { return z(c - 1, r) + z(c + 1, r) + z(c, r - 1) + z(c, r + 1) - 4.0 * z(c, r); };
      const double dz = h.at(c, r) - hillHeight(height, c, r);
      const double dl = laplacian([&](int i, int j) { return h.at(i, j); }) -
                        laplacian([&](int i, int j) { return hillHeight(height, i, j); });
      z2 += dz * dz;
      l2 += dl * dl;
      ++count;
    }
  }
  return {std::sqrt(z2 / count), std::sqrt(l2 / count)};
}

}  // namespace shanshui::test

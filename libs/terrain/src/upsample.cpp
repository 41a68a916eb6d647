// A coarse grid made finer by bicubic interpolation (heightfield.h's upsample).

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

#include <opencv2/core.hpp>

#include "shanshui/core/error.h"
#include "shanshui/terrain/heightfield.h"

namespace shanshui::terrain {

void upsample(Heightfield& h, int factor, const std::string& what) {
  if (factor < 1 || factor > kMostUpsample) {
    throw makeError(what, ": ", factor, " is not an upsampling factor; expected a whole number from 1 to ",
                    kMostUpsample);
  }
  if (factor == 1 || h.columns < 2 || h.rows < 2) return;
  const int w = h.columns, n = h.rows;
  const int fine_w = (w - 1) * factor + 1, fine_n = (n - 1) * factor + 1;
  if (upsampledSamples(h, factor) > static_cast<double>(kMaxGridSamples)) {
    throw makeError(what, ": ", w, " x ", n, " samples ", factor, " times finer is ", fine_w, " x ", fine_n,
                    ", more than the ", kMaxGridSamples, " samples a grid may hold");
  }
  // The heights the interpolation reads: a no-data sample takes the mean of its valid
  // neighbours (8-neighbours), the rest 0. Only new samples whose cell has valid corners are
  // kept, and the cubic reads the samples one beyond those corners, each a neighbour of a
  // valid corner: so the stand-ins shape the ground only at a hole's rim, continuing it.
  cv::Mat z(n, w, CV_64F), valid(n, w, CV_8U);
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < w; ++c) {
      const double e = h.at(c, r);
      valid.at<unsigned char>(r, c) = std::isnan(e) ? 0 : 1;
      z.at<double>(r, c) = std::isnan(e) ? 0.0 : e;
    }
  }
  const bool holes = cv::countNonZero(valid) < w * n;
  if (holes) {
    const cv::Mat stored = z.clone();
    for (int r = 0; r < n; ++r) {
      for (int c = 0; c < w; ++c) {
        if (valid.at<unsigned char>(r, c)) continue;
        double sum = 0.0;
        int count = 0;
        for (int rr = std::max(r - 1, 0); rr <= std::min(r + 1, n - 1); ++rr) {
          for (int cc = std::max(c - 1, 0); cc <= std::min(c + 1, w - 1); ++cc) {
            if (!valid.at<unsigned char>(rr, cc)) continue;
            sum += stored.at<double>(rr, cc);
            ++count;
          }
        }
        if (count > 0) z.at<double>(r, c) = sum / count;
      }
    }
  }
  // Catmull-Rom (the cubic that passes through the samples and reproduces quadratics: Keys'
  // a = −0.5), along the rows and then along the columns, at the exact fractions k / factor.
  // OpenCV's cubic (a = −0.75, in remap at positions rounded to 1/32) is a softer filter: on
  // a landform of 7-cell waves it missed by 0.35 times what straight lines between the
  // samples miss, this one by 0.12 times. Beyond the edges the heights go on as the
  // parabola through the last three samples would, so that quadratics are kept to the edge
  // (the ghost sample weighs at most 0.074 in the last cell).
  auto weights = [](double t) {
    const double t2 = t * t, t3 = t2 * t;
    return std::array<double, 4>{0.5 * (-t3 + 2.0 * t2 - t), 0.5 * (3.0 * t3 - 5.0 * t2 + 2.0),
                                 0.5 * (-3.0 * t3 + 4.0 * t2 + t), 0.5 * (t3 - t2)};
  };
  auto along = [&](auto get, int count, int k) {  // a line of `count` samples, at k / factor
    const int i = std::min(k / factor, count - 2);
    const double t = static_cast<double>(k - i * factor) / factor;
    const std::array<double, 4> wt = weights(t);
    auto sample = [&](int j) {  // j from −1 to count
      const int e = j < 0 ? 0 : count - 1, in = j < 0 ? 1 : -1;
      if (j >= 0 && j < count) return get(j);
      if (count < 3) return 2.0 * get(e) - get(e + in);
      return 3.0 * get(e) - 3.0 * get(e + in) + get(e + 2 * in);
    };
    return wt[0] * sample(i - 1) + wt[1] * sample(i) + wt[2] * sample(i + 1) + wt[3] * sample(i + 2);
  };
  cv::Mat rows_done(n, fine_w, CV_64F), fine(fine_n, fine_w, CV_64F);
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < fine_w; ++c)
      rows_done.at<double>(r, c) = along([&](int j) { return z.at<double>(r, j); }, w, c);
  for (int r = 0; r < fine_n; ++r)
    for (int c = 0; c < fine_w; ++c)
      fine.at<double>(r, c) = along([&](int j) { return rows_done.at<double>(j, c); }, n, r);
  std::vector<double> out(static_cast<std::size_t>(fine_w) * fine_n);
  for (int r = 0; r < fine_n; ++r) {
    const int r0 = r / factor, r1 = std::min(r0 + (r % factor ? 1 : 0), n - 1);
    for (int c = 0; c < fine_w; ++c) {
      const int c0 = c / factor, c1 = std::min(c0 + (c % factor ? 1 : 0), w - 1);
      double& e = out[static_cast<std::size_t>(r) * fine_w + c];
      if (r % factor == 0 && c % factor == 0) {
        e = h.at(c0, r0);  // a stored sample, exactly (and no data stays so)
        continue;
      }
      const bool kept = !holes || (valid.at<unsigned char>(r0, c0) && valid.at<unsigned char>(r0, c1) &&
                                   valid.at<unsigned char>(r1, c0) && valid.at<unsigned char>(r1, c1));
      if (!kept) {
        e = kNoData;
        continue;
      }
      e = fine.at<double>(r, c);
      if (!std::isfinite(e)) {
        // Heights near the largest double overflow the cubic's sums: straight lines between
        // the cell's corners there, which stay within them.
        const double tx = static_cast<double>(c % factor) / factor, ty = static_cast<double>(r % factor) / factor;
        const double top = (1.0 - tx) * h.at(c0, r0) + tx * h.at(c1, r0);
        const double bottom = (1.0 - tx) * h.at(c0, r1) + tx * h.at(c1, r1);
        e = (1.0 - ty) * top + ty * bottom;
      }
    }
  }
  h.elevation = std::move(out);
  h.columns = fine_w;
  h.rows = fine_n;
  h.cell_x /= factor;
  h.cell_y /= factor;
  std::ostringstream note;
  note << w << " x " << n << " samples made " << factor << " times finer (" << fine_w << " x " << fine_n
       << ", bicubic), so the grid's cells are not drawn as facets";
  h.notes.push_back(note.str());
}

double upsampledSamples(const Heightfield& h, int factor) {
  return (static_cast<double>(h.columns - 1) * factor + 1.0) * (static_cast<double>(h.rows - 1) * factor + 1.0);
}

int upsampleFactor(const Heightfield& h, int least_side, std::size_t max_samples) {
  const int side = std::max(h.columns, h.rows);
  if (side < 2 || side >= least_side) return 1;
  int factor = 1;
  while (factor < kMostUpsample && (side - 1) * factor + 1 < least_side) {
    if (upsampledSamples(h, factor + 1) > static_cast<double>(max_samples)) break;
    ++factor;
  }
  return factor;
}

}  // namespace shanshui::terrain

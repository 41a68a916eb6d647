// Graph-cut seams (Kwatra, Schödl, Essa, Turk, Bobick 2003, section 3) on OpenCV's
// Boykov–Kolmogorov max-flow (imgproc/detail/gcgraph.hpp, the solver behind GrabCut).
// gcgraph.hpp is not self-contained: it needs <climits>, <vector> and OpenCV's core first.
#include <climits>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgproc/detail/gcgraph.hpp>

#include "shanshui/core/error.h"
#include "shanshui/texsynth/seam.h"

namespace shanshui::texsynth {

cv::Mat graphCutMask(const image::Image& old, const image::Image& patch, const cv::Mat& filled) {
  const int b = filled.rows;
  const OverlapStrips strips = overlapStrips(filled);
  // ‖old − new‖ per pixel (the matching cost of Kwatra et al., Eq. 1).
  cv::Mat norm = overlapDifference(old, patch, filled);
  cv::sqrt(norm, norm);

  cv::Mat node(b, b, CV_32S, cv::Scalar(-1));
  int nodes = 0;
  for (int y = 0; y < b; ++y) {
    for (int x = 0; x < b; ++x) {
      if (filled.at<std::uint8_t>(y, x)) node.at<int>(y, x) = nodes++;
    }
  }
  cv::Mat isNew(b, b, CV_8U, cv::Scalar(1));
  if (nodes == 0) return isNew;

  // A hard constraint outweighs every possible cut: at most 2 edges per node, each costing
  // at most twice the largest per-pixel difference.
  double largest = 0.0;
  cv::minMaxLoc(norm, nullptr, &largest);
  const double hard = 1.0 + 4.0 * nodes * largest;
  cv::detail::GCGraph<double> graph(static_cast<unsigned>(nodes), static_cast<unsigned>(4 * nodes));
  for (int i = 0; i < nodes; ++i) graph.addVtx();
  auto filledAt = [&](int x, int y) { return filled.at<std::uint8_t>(y, x) != 0; };
  for (int y = 0; y < b; ++y) {
    for (int x = 0; x < b; ++x) {
      const int n = node.at<int>(y, x);
      if (n < 0) continue;
      if (x + 1 < b && filledAt(x + 1, y)) {
        const double w = norm.at<double>(y, x) + norm.at<double>(y, x + 1);
        graph.addEdges(n, node.at<int>(y, x + 1), w, w);
      }
      if (y + 1 < b && filledAt(x, y + 1)) {
        const double w = norm.at<double>(y, x) + norm.at<double>(y + 1, x);
        graph.addEdges(n, node.at<int>(y + 1, x), w, w);
      }
      // Tied to the old side: on a block edge that borders earlier blocks.
      const bool keepOld = (x == 0 && strips.left > 0) || (x == b - 1 && strips.right > 0) ||
                           (y == 0 && strips.top > 0) || (y == b - 1 && strips.bottom > 0);
      // Tied to the new side: next to a pixel only the new block covers.
      const bool takeNew = (x > 0 && !filledAt(x - 1, y)) || (x + 1 < b && !filledAt(x + 1, y)) ||
                           (y > 0 && !filledAt(x, y - 1)) || (y + 1 < b && !filledAt(x, y + 1));
      if (keepOld || takeNew) graph.addTermWeights(n, keepOld ? hard : 0.0, takeNew ? hard : 0.0);
    }
  }
  graph.maxFlow();
  for (int y = 0; y < b; ++y) {
    for (int x = 0; x < b; ++x) {
      const int n = node.at<int>(y, x);
      if (n >= 0 && graph.inSourceSegment(n)) isNew.at<std::uint8_t>(y, x) = 0;
    }
  }
  return isNew;
}

}  // namespace shanshui::texsynth

#include "plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "shanshui/core/atomic_output.h"
#include "shanshui/core/error.h"

namespace shanshui::bench {
namespace {

std::vector<double> finite(const std::vector<double>& v) {
  std::vector<double> f;
  for (double x : v)
    if (std::isfinite(x)) f.push_back(x);
  return f;
}

// 1, 2 or 5 times a power of ten, close to span/5.
double niceStep(double span) {
  const double raw = span / 5.0, p = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0})
    if (m * p >= raw) return m * p;
  return 10.0 * p;
}

std::string tickLabel(double v) {
  char buf[32];
  if (v != 0.0 && (std::abs(v) < 1e-3 || std::abs(v) >= 1e5))
    std::snprintf(buf, sizeof buf, "%.0e", v);
  else
    std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

const cv::Scalar kPalette[] = {{180, 119, 31}, {14, 127, 255},  {44, 160, 44},   {40, 39, 214},  {189, 103, 148},
                               {75, 86, 140},  {194, 119, 227}, {127, 127, 127}, {34, 189, 188}, {207, 190, 23}};

void text(cv::Mat& img, const std::string& s, cv::Point at, double scale = 0.45, cv::Scalar colour = {0, 0, 0}) {
  cv::putText(img, s, at, cv::FONT_HERSHEY_SIMPLEX, scale, colour, 1, cv::LINE_AA);
}

int textWidth(const std::string& s, double scale = 0.45) {
  int base = 0;
  return cv::getTextSize(s, cv::FONT_HERSHEY_SIMPLEX, scale, 1, &base).width;
}

}  // namespace

double Axis::map(double v) const {
  const double t = log ? std::log10(v) : v;
  return hi > lo ? (t - lo) / (hi - lo) : 0.5;
}

Axis chooseAxis(const std::vector<double>& values) {
  Axis a;
  const std::vector<double> v = finite(values);
  if (v.empty()) {
    a.ticks = {0.0, 1.0};
    return a;
  }
  const auto [mn, mx] = std::minmax_element(v.begin(), v.end());
  double lo = *mn, hi = *mx;
  a.log = lo > 0.0 && hi / lo > 20.0;
  if (a.log) {
    a.lo = std::floor(std::log10(lo));
    a.hi = std::ceil(std::log10(hi));
    const int decades = static_cast<int>(a.hi - a.lo);
    const int every = std::max(1, decades / 8);  // at most ~8 labelled decades
    for (int e = static_cast<int>(a.lo); e <= static_cast<int>(a.hi); e += every) a.ticks.push_back(std::pow(10.0, e));
    return a;
  }
  if (hi == lo) {  // a single value: a range around it
    const double pad = lo == 0.0 ? 1.0 : std::abs(lo) * 0.1;
    lo -= pad;
    hi += pad;
  }
  const double step = niceStep(hi - lo);
  a.lo = std::floor(lo / step) * step;
  a.hi = std::ceil(hi / step) * step;
  for (double t = a.lo; t <= a.hi + step * 1e-9; t += step) a.ticks.push_back(std::abs(t) < step * 1e-9 ? 0.0 : t);
  return a;
}

void writePlot(const Plot& plot, const std::filesystem::path& png) {
  const int width = 900, height = 560, left = 80, right = 250, top = 56, bottom = 56;
  const int plotW = width - left - right, plotH = height - top - bottom;
  cv::Mat img(height, width, CV_8UC3, cv::Scalar(255, 255, 255));

  std::vector<double> xs, ys;
  for (const Series& s : plot.series) {
    for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      xs.push_back(s.x[i]);
      ys.push_back(s.y[i]);
    }
  }
  const Axis ax = chooseAxis(xs), ay = chooseAxis(ys);
  auto px = [&](double x, double y) {
    return cv::Point(left + static_cast<int>(std::lround(ax.map(x) * plotW)),
                     top + plotH - static_cast<int>(std::lround(ay.map(y) * plotH)));
  };
  const bool drawable = !xs.empty();
  text(img, plot.title, {left, 24}, 0.6);
  text(img, plot.y_label + (ay.log ? " (log)" : ""), {left, top - 10}, 0.45, {60, 60, 60});
  const std::string xl = plot.x_label + (ax.log ? " (log)" : "");
  text(img, xl, {left + plotW / 2 - textWidth(xl) / 2, height - 14}, 0.45, {60, 60, 60});
  cv::rectangle(img, {left, top}, {left + plotW, top + plotH}, {0, 0, 0}, 1);
  for (double t : ax.ticks) {
    const int x = left + static_cast<int>(std::lround(ax.map(t) * plotW));
    cv::line(img, {x, top}, {x, top + plotH}, {225, 225, 225}, 1);
    const std::string l = tickLabel(t);
    text(img, l, {x - textWidth(l, 0.4) / 2, top + plotH + 18}, 0.4);
  }
  for (double t : ay.ticks) {
    const int y = top + plotH - static_cast<int>(std::lround(ay.map(t) * plotH));
    cv::line(img, {left, y}, {left + plotW, y}, {225, 225, 225}, 1);
    const std::string l = tickLabel(t);
    text(img, l, {left - 8 - textWidth(l, 0.4), y + 4}, 0.4);
  }
  cv::rectangle(img, {left, top}, {left + plotW, top + plotH}, {0, 0, 0}, 1);
  if (!drawable) text(img, "no data", {left + plotW / 2 - 30, top + plotH / 2}, 0.6, {0, 0, 200});

  int legendY = top + 8;
  for (std::size_t k = 0; k < plot.series.size(); ++k) {
    const Series& s = plot.series[k];
    const cv::Scalar c = kPalette[k % std::size(kPalette)];
    std::vector<cv::Point> pts;
    for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i)
      if (std::isfinite(s.x[i]) && std::isfinite(s.y[i])) pts.push_back(px(s.x[i], s.y[i]));
    if (s.joined && pts.size() > 1) cv::polylines(img, pts, false, c, 2, cv::LINE_AA);
    for (const cv::Point& p : pts) cv::circle(img, p, 4, c, cv::FILLED, cv::LINE_AA);
    // Legend: marker and label, long labels cut to the legend's width.
    std::string label = s.label;
    while (label.size() > 4 && textWidth(label, 0.42) > right - 40) label = label.substr(0, label.size() - 4) + "...";
    cv::line(img, {left + plotW + 14, legendY}, {left + plotW + 34, legendY}, c, 2, cv::LINE_AA);
    cv::circle(img, {left + plotW + 24, legendY}, 4, c, cv::FILLED, cv::LINE_AA);
    text(img, label, {left + plotW + 40, legendY + 5}, 0.42);
    legendY += 20;
  }
  writeAtomically(png, [&](const std::filesystem::path& tmp) {
    if (!cv::imwrite(tmp.string(), img)) throw makeError(png.string(), ": cannot write the plot");
  });
}

}  // namespace shanshui::bench

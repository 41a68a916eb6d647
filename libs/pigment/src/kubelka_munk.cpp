#include "shanshui/pigment/kubelka_munk.h"

#include <cmath>

#include "shanshui/core/error.h"

namespace shanshui::pigment {

Coefficients coefficients(const Pigment& p, const char* what) {
  Coefficients c;
  static const char* kChannel[3] = {"red", "green", "blue"};
  for (int i = 0; i < 3; ++i) {
    const double w = p.on_white[i], k = p.on_black[i];
    if (!(w > 0.0 && w < 1.0) || !(k > 0.0 && k < 1.0))
      throw makeError(what, ": ", kChannel[i], " on white ", w, ", on black ", k, ": expected both in (0, 1)");
    if (!(k < w))
      throw makeError(what, ": ", kChannel[i], " on black ", k, " is not darker than on white ", w,
                      ": expected on_black < on_white");
    // Curtis et al. 1997 §5.1: a from the two reflectances, b = √(a² − 1), S from the
    // layer over black, K = S (a − 1). (1 − w)(1 − k) > 0 makes a > 1.
    const double a = 0.5 * (w + (k - w + 1.0) / k);
    const double b = std::sqrt(a * a - 1.0);
    const double z = (b * b - (a - w) * (a - 1.0)) / (b * (1.0 - w));
    const double S = 0.5 * std::log((z + 1.0) / (z - 1.0)) / b;  // arccoth(z) / b
    c.a[i] = a;
    c.b[i] = b;
    c.S[i] = S;
    c.K[i] = S * (a - 1.0);
  }
  return c;
}

Layer layer(const Coefficients& c, double thickness) {
  SHANSHUI_CHECK(thickness >= 0.0);
  Layer l;
  for (int i = 0; i < 3; ++i) {
    // sinh and cosh of x = b S t, written with e^(-x) so that no term overflows:
    // R = sinh / (a sinh + b cosh), T = b / (a sinh + b cosh).
    const double x = c.b[i] * c.S[i] * thickness;
    const double e1 = std::exp(-x), e2 = e1 * e1;
    const double d = c.a[i] * (1.0 - e2) + c.b[i] * (1.0 + e2);
    l.R[i] = l.R_below[i] = (1.0 - e2) / d;
    l.T[i] = 2.0 * c.b[i] * e1 / d;
  }
  return l;
}

Layer over(const Layer& top, const Layer& bottom) {
  Layer l;
  for (int i = 0; i < 3; ++i) {
    // Light bounces between the top's underside and the bottom's upper side (Curtis et al.
    // write it for layers that look alike from both sides).
    const double bounce = 1.0 / (1.0 - top.R_below[i] * bottom.R[i]);
    l.R[i] = top.R[i] + top.T[i] * top.T[i] * bottom.R[i] * bounce;
    l.R_below[i] = bottom.R_below[i] + bottom.T[i] * bottom.T[i] * top.R_below[i] * bounce;
    l.T[i] = top.T[i] * bottom.T[i] * bounce;
  }
  return l;
}

glm::dvec3 onSubstrate(const Layer& l, glm::dvec3 substrate) {
  Layer ground;
  ground.R = ground.R_below = substrate;
  ground.T = glm::dvec3(0.0);
  return over(l, ground).R;
}

}  // namespace shanshui::pigment

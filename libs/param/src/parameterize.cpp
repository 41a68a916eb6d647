#include "shanshui/param/parameterize.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>

#include "arap_refine.h"
#include "cgal_methods.h"
#include "shanshui/core/error.h"
#include "shanshui/param/seam_cut.h"

namespace shanshui::param {
namespace {

using Clock = std::chrono::steady_clock;

const std::pair<Method, const char*> kMethodNames[] = {
    {Method::Auto, "auto"},     {Method::Xy, "xy"},     {Method::Mvc, "mvc"},   {Method::Dcm, "dcm"},
    {Method::Tutte, "tutte"},   {Method::Lscm, "lscm"}, {Method::Arap, "arap"}, {Method::Authalic, "authalic"},
    {Method::Charts, "charts"},
};

std::uint64_t edgeKey(std::uint32_t a, std::uint32_t b) {
  return (static_cast<std::uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
}

int findRoot(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

// Border loops and edge count of a triangle mesh, from one sorted list of undirected edges
// (an edge used by one triangle is a border edge).
struct Topology {
  int border_loops = 0;
  std::size_t edges = 0;
};

Topology topology(const mesh::Mesh& m) {
  std::vector<std::uint64_t> keys;
  keys.reserve(3 * m.triangles.size());
  for (const glm::uvec3& t : m.triangles) {
    keys.push_back(edgeKey(t.x, t.y));
    keys.push_back(edgeKey(t.y, t.z));
    keys.push_back(edgeKey(t.z, t.x));
  }
  std::sort(keys.begin(), keys.end());
  std::vector<int> parent(m.positions.size());
  std::iota(parent.begin(), parent.end(), 0);
  std::vector<bool> onBorder(m.positions.size(), false);
  Topology top;
  for (std::size_t e = 0; e < keys.size();) {
    std::size_t f = e + 1;
    while (f < keys.size() && keys[f] == keys[e]) ++f;
    ++top.edges;
    if (f - e == 1) {
      const int a = static_cast<int>(keys[e] >> 32), b = static_cast<int>(keys[e] & 0xffffffffu);
      onBorder[a] = onBorder[b] = true;
      parent[findRoot(parent, a)] = findRoot(parent, b);
    }
    e = f;
  }
  for (std::size_t v = 0; v < parent.size(); ++v) {
    top.border_loops += onBorder[v] && findRoot(parent, static_cast<int>(v)) == static_cast<int>(v);
  }
  return top;
}

std::vector<glm::dvec2> runMethod(const mesh::Mesh& m, Method method, const ParamOptions& opts) {
  switch (method) {
    case Method::Xy: {
      std::vector<glm::dvec2> uv(m.positions.size());
      for (std::size_t i = 0; i < uv.size(); ++i) uv[i] = {m.positions[i].x, m.positions[i].y};
      return uv;
    }
    case Method::Mvc:
    case Method::Dcm:
    case Method::Tutte:
    case Method::Authalic:
      return detail::fixedBorderUvs(m, method, opts.border, opts.authalic_iterations);
    case Method::Lscm:
    case Method::Arap:
      return detail::freeBorderUvs(m, method);
    case Method::Auto:
    case Method::Charts:
      break;
  }
  SHANSHUI_CHECK(false);
  return {};
}

// Runs one method and measures it; UVs are made counter-clockwise (mirrored in v if the
// method produced a clockwise map) so "flipped" means folded, not mirrored.
MethodTrial tryMethod(const mesh::Mesh& m, Method method, const ParamOptions& opts, mesh::Mesh* result) {
  MethodTrial trial;
  trial.method = method;
  const auto start = Clock::now();
  std::vector<glm::dvec2> uv;
  try {
    uv = runMethod(m, method, opts);
  } catch (const Error& e) {
    trial.note = e.what();
    trial.seconds = std::chrono::duration<double>(Clock::now() - start).count();
    return trial;
  }
  trial.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  trial.ran = true;
  double signedArea = 0.0;
  for (const glm::uvec3& t : m.triangles) {
    const glm::dvec2 a = uv[t.x], b = uv[t.y], c = uv[t.z];
    signedArea += (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
  }
  *result = m;
  result->uvs.resize(uv.size());
  for (std::size_t i = 0; i < uv.size(); ++i) {
    result->uvs[i] = glm::vec2(static_cast<float>(uv[i].x), static_cast<float>(signedArea < 0 ? -uv[i].y : uv[i].y));
  }
  trial.distortion = measureDistortion(*result);
  return trial;
}

// Seconds each method took in bench_param_tradeoff on the development machine (2 cores),
// as a function of the vertex count: linear for the projection, n^1.5 for the sparse
// direct solves, and for ARAP the worst case of its 50 iterations (one LSCM-sized solve
// each: 0.4 s at 16k vertices on a terrain, which converges at once, but 2.7 s on the 7.5k
// vertices of CGAL's lion). Charts: about linear (segmentation, one LSCM per chart,
// merging), 1.1 s for the 2.9k vertices of the cow and 6 s for the 38k of the bunny.
double modelSeconds(Method method, double vertices) {
  const double k = vertices / 16500.0;
  switch (method) {
    case Method::Xy:
      return 0.012 * k;
    case Method::Mvc:
    case Method::Dcm:
    case Method::Tutte:
      return 0.22 * std::pow(k, 1.5);
    case Method::Lscm:
      return 0.25 * std::pow(k, 1.5);
    case Method::Arap:
      return 51 * 0.25 * std::pow(k, 1.5);
    case Method::Authalic:
      return 6.0 * std::pow(k, 1.5);
    case Method::Charts:
      return 4.5 * k;
    case Method::Auto:
      break;
  }
  return 0.0;
}

// Predictions are off by tens of percent on a busy machine: a method must fit with this
// much to spare.
constexpr double kBudgetMargin = 1.25;
// Refinement stops at this share of the budget: the clock is read between rounds' pieces
// (up to ~0.1 s apart on 250k vertices), and the map is measured after it.
constexpr double kRefineShare = 0.93;

std::string describe(const Distortion& d) {
  std::ostringstream s;
  s << d.flipped << " flipped, " << d.degenerate << " degenerate and " << d.non_finite << " non-finite UV faces";
  return s.str();
}

}  // namespace

const char* methodName(Method m) {
  for (const auto& [method, name] : kMethodNames)
    if (method == m) return name;
  return "?";
}

Method parseMethod(const std::string& text) {
  for (const auto& [method, name] : kMethodNames)
    if (text == name) return method;
  throw makeError("--method: unknown method '", text, "'; expected auto, xy, mvc, dcm, tutte, lscm, arap or authalic");
}

const char* borderName(Border b) {
  return b == Border::Square ? "square" : "circle";
}

Border parseBorder(const std::string& text) {
  if (text == "circle") return Border::Circle;
  if (text == "square") return Border::Square;
  throw makeError("--border: unknown border '", text, "'; expected circle or square");
}

int borderLoops(const mesh::Mesh& m) {
  return topology(m).border_loops;
}

std::string trialSummary(const ParamReport& r) {
  std::ostringstream s;
  s.precision(3);
  for (const MethodTrial& t : r.trials) {
    if (!t.ran) continue;
    s << (s.tellp() > 0 ? "; " : "") << methodName(t.method) << " ";
    if (t.distortion.valid()) {
      s << "L2 " << t.distortion.l2_stretch;
    } else {
      s << describe(t.distortion);
    }
  }
  return s.str();
}

std::string trialTable(const ParamReport& r) {
  std::ostringstream s;
  s.precision(3);
  for (const MethodTrial& t : r.trials) {
    s << "  " << methodName(t.method) << ": ";
    if (t.ran) {
      s << t.seconds << " s (predicted " << t.predicted_seconds << " s), ";
      if (t.distortion.valid()) {
        s << "L2 stretch " << t.distortion.l2_stretch;
      } else {
        s << describe(t.distortion);
      }
    } else {
      s << t.note;
    }
    s << "\n";
  }
  for (const Refinement& f : r.refinements) {
    s << "  refine (ARAP rounds from " << methodName(f.from) << "): " << f.seconds << " s, " << f.rounds << " rounds, "
      << (f.converged ? "converged"
          : f.enough  ? "good enough"
                      : "until the budget ran out")
      << ", ";
    if (f.distortion.valid()) {
      s << "L2 stretch " << f.distortion.l2_stretch;
    } else {
      s << describe(f.distortion);
    }
    s << (f.kept ? " (kept)" : " (not kept)") << "\n";
  }
  return s.str();
}

mesh::Mesh parameterize(const mesh::Mesh& input, const ParamOptions& opts, ParamReport* report,
                        const std::string& what) {
  if (opts.authalic_iterations < 1 || opts.authalic_iterations > 1000) {
    throw makeError("authalic iterations ", opts.authalic_iterations, "; expected [1, 1000]");
  }
  if (!(opts.auto_accept_stretch >= 1.0)) {
    throw makeError("auto stretch limit ", opts.auto_accept_stretch, "; expected at least 1");
  }
  if (!(opts.budget_seconds >= 0.0)) {
    throw makeError("--budget ", opts.budget_seconds, "; expected seconds >= 0");
  }
  if (!(opts.max_stretch >= 1.0)) throw makeError("--max-stretch ", opts.max_stretch, "; expected at least 1");
  if (!(opts.one_piece_preference >= 1.0)) {
    throw makeError("one-piece preference ", opts.one_piece_preference, "; expected at least 1");
  }
  if (input.triangles.empty()) throw makeError(what, ": no triangles to parameterize");
  for (const glm::dvec3& p : input.positions) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw makeError(what, ": NaN or infinite vertex coordinates; repair the mesh first");
  }
  const auto start = Clock::now();
  ParamReport local;
  ParamReport& r = report ? *report : local;
  r = {};

  // The one-piece methods need a disc: the input, or a closed sphere-like mesh cut open.
  mesh::Mesh disc;
  std::string notADisc;
  const Topology top = topology(input);
  const long long euler = static_cast<long long>(input.positions.size()) - static_cast<long long>(top.edges) +
                          static_cast<long long>(input.triangles.size());
  if (top.border_loops == 0) {
    try {
      SeamCut cut = cutOpen(input, what);
      disc = std::move(cut.mesh);
      r.seam_vertices = static_cast<int>(cut.seam.size());
    } catch (const Error& e) {
      notADisc = e.what();
    }
  } else if (top.border_loops > 1) {
    notADisc = makeError(what, ": ", top.border_loops,
                         " border loops (holes or several components); fill the holes "
                         "and keep one component first (shanshui-repair)")
                   .what();
  } else if (euler != 1) {
    notADisc = makeError(what, ": not a topological disc (Euler characteristic ", euler,
                         ", expected 1: handles or several components)")
                   .what();
  } else {
    disc = input;
  }
  // Recentred in double: UTM-sized coordinates would lose precision in the solvers.
  mesh::Mesh m = disc;
  glm::dvec3 centre(0.0);
  for (const glm::dvec3& p : m.positions) centre += p;
  centre /= std::max<double>(1.0, static_cast<double>(m.positions.size()));
  for (glm::dvec3& p : m.positions) p -= centre;

  // Each candidate is run and measured; the best one-piece map and the atlas are kept apart.
  mesh::Mesh bestPiece, atlas;
  Distortion pieceDistortion, atlasDistortion;
  Method pieceMethod = Method::Xy;
  bool havePiece = false, haveAtlas = false;
  bool refinedPiece = false;   // the best one-piece map came from refinement
  bool bestConverged = false;  // refinement of the best one-piece map has nothing more to give
  AtlasReport atlasReport;
  double speed = 1.0;  // measured seconds / modelled seconds, from the last method that ran long enough
  auto run = [&](Method method) {
    MethodTrial trial;
    trial.method = method;
    const double vertices = static_cast<double>(method == Method::Charts ? input.positions.size() : m.positions.size());
    trial.predicted_seconds = speed * modelSeconds(method, vertices);
    if (method == Method::Charts) {
      const auto t0 = Clock::now();
      AtlasReport ar;
      try {
        mesh::Mesh result = parameterizeCharts(input, opts.charts, &ar, what);
        trial.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
        trial.ran = true;
        trial.distortion = measureDistortion(result);
        if (trial.distortion.valid()) {
          atlas = std::move(result);
          atlasDistortion = trial.distortion;
          atlasReport = std::move(ar);
          haveAtlas = true;
        }
      } catch (const Error& e) {
        trial.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
        trial.note = e.what();
      }
    } else {
      mesh::Mesh result;
      const double predicted = trial.predicted_seconds;
      trial = tryMethod(m, method, opts, &result);
      trial.predicted_seconds = predicted;
      if (trial.ran && trial.distortion.valid() &&
          (!havePiece || trial.distortion.l2_stretch < pieceDistortion.l2_stretch)) {
        bestPiece = std::move(result);
        pieceDistortion = trial.distortion;
        pieceMethod = method;
        havePiece = true;
        refinedPiece = bestConverged = false;
      }
    }
    // The machine's speed, from the methods whose cost depends on size alone (ARAP's
    // iterations and the number of charts depend on the shape).
    const double modelled = modelSeconds(method, vertices);
    const bool steady = method != Method::Arap && method != Method::Charts;
    if (steady && trial.ran && trial.seconds > 0.05 && modelled > 0.0) {
      speed = std::clamp(trial.seconds / modelled, 0.25, 20.0);
    }
    r.trials.push_back(std::move(trial));
  };
  auto bestStretch = [&] {
    double best = std::numeric_limits<double>::infinity();
    if (havePiece) best = pieceDistortion.l2_stretch;
    if (haveAtlas) best = std::min(best, atlasDistortion.l2_stretch);
    return best;
  };

  if (opts.method != Method::Auto) {
    if (opts.method != Method::Charts && !notADisc.empty()) {
      throw makeError(notADisc, "; --method charts (or auto) makes an atlas of charts instead");
    }
    run(opts.method);
    const MethodTrial& t = r.trials.back();
    if (!t.ran) throw makeError(what, ": ", t.note);
    if (!havePiece && !haveAtlas) {
      throw makeError(what, ": ", methodName(opts.method), " gives ", describe(t.distortion), " of ",
                      t.distortion.faces, "; try --method auto");
    }
    r.decision = std::string("asked for ") + methodName(opts.method);
  } else {
    // ARAP rounds from the best one-piece map while it is above the early stop, until
    // `share` of the time left to the deadline is spent or the rounds stop gaining: after
    // the projection with half of it (on a terrain the projection refined beats every
    // solver), and after the plan with the rest, so the budget is used, not idled.
    const auto deadline = start + std::chrono::duration_cast<Clock::duration>(
                                      std::chrono::duration<double>(kRefineShare * opts.budget_seconds));
    auto refine = [&](double share) {
      if (!opts.refine || !havePiece || bestConverged || pieceDistortion.l2_stretch <= opts.auto_accept_stretch) return;
      const auto t0 = Clock::now();
      if (t0 >= deadline) return;
      const auto until = t0 + std::chrono::duration_cast<Clock::duration>(share * (deadline - t0));
      std::vector<glm::dvec2> uv(bestPiece.uvs.begin(), bestPiece.uvs.end());
      mesh::Mesh refined = bestPiece;
      auto setUvs = [&](const std::vector<glm::dvec2>& from) {
        for (std::size_t i = 0; i < from.size(); ++i) refined.uvs[i] = glm::vec2(from[i]);
      };
      // Good enough ends it, as it ends the plan.
      const detail::RefineResult rr =
          detail::refineArap(bestPiece, uv, until, 1e-5, [&](const std::vector<glm::dvec2>& so_far) {
            setUvs(so_far);
            const Distortion d = measureDistortion(refined);
            return d.valid() && d.l2_stretch <= opts.auto_accept_stretch;
          });
      setUvs(uv);
      Refinement f;
      f.from = pieceMethod;
      f.rounds = rr.iterations;
      f.converged = rr.converged;
      f.enough = rr.enough;
      f.distortion = measureDistortion(refined);
      f.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
      f.kept = f.distortion.valid() && f.distortion.l2_stretch < pieceDistortion.l2_stretch;
      if (f.kept) {
        bestPiece = std::move(refined);
        pieceDistortion = f.distortion;
        refinedPiece = true;
      }
      bestConverged = f.converged || !f.kept;  // no point going on from the same map
      r.refinements.push_back(f);
    };
    // Cheapest and most likely first. A closed or non-disc mesh starts with the atlas: one
    // seam rarely flattens an animal or a statue (SPEC.md section 5).
    std::vector<Method> plan;
    if (notADisc.empty() && r.seam_vertices == 0) {
      plan = {Method::Xy, Method::Mvc, Method::Lscm, Method::Charts, Method::Arap, Method::Tutte};
    } else if (notADisc.empty()) {
      plan = {Method::Charts, Method::Mvc, Method::Lscm, Method::Arap, Method::Tutte};
    } else {
      plan = {Method::Charts};
    }
    for (Method method : plan) {
      const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
      const double predicted =
          speed * modelSeconds(method, static_cast<double>(method == Method::Charts ? input.positions.size()
                                                                                    : m.positions.size()));
      std::ostringstream why;
      why.precision(3);
      if (bestStretch() <= opts.auto_accept_stretch) {
        why << "skipped: a valid map with L2 stretch <= " << opts.auto_accept_stretch << " is already found";
      } else if (!r.trials.empty() && elapsed + kBudgetMargin * predicted > opts.budget_seconds) {
        why << "skipped: predicted " << predicted << " s, " << std::max(0.0, opts.budget_seconds - elapsed)
            << " s of the " << opts.budget_seconds << " s budget left";
      }
      if (!why.str().empty()) {
        MethodTrial skipped;
        skipped.method = method;
        skipped.predicted_seconds = predicted;
        skipped.note = why.str();
        r.trials.push_back(std::move(skipped));
        continue;
      }
      run(method);
      if (method == Method::Xy) refine(0.5);
    }
    refine(1.0);
    if (!havePiece && !haveAtlas) {
      throw makeError(what, ": no method gave a one-to-one parameterization",
                      notADisc.empty() ? "" : " (" + notADisc + ")", "; tried ", trialSummary(r));
    }
  }

  // An atlas has seams the wrinkle strokes break at, so a one-piece map within the
  // preference factor of it wins.
  const bool keepAtlas =
      haveAtlas && (!havePiece || pieceDistortion.l2_stretch > opts.one_piece_preference * atlasDistortion.l2_stretch);
  std::ostringstream decision;
  decision.precision(4);
  mesh::Mesh best;
  if (keepAtlas) {
    best = std::move(atlas);
    r.method = Method::Charts;
    r.distortion = atlasDistortion;
    r.atlas = std::move(atlasReport);
    r.seam_vertices = 0;
    decision << "charts: L2 stretch " << atlasDistortion.l2_stretch;
    if (havePiece) {
      decision << " against " << pieceDistortion.l2_stretch << " for the best one-piece map ("
               << methodName(pieceMethod) << ")";
    }
  } else {
    best = std::move(bestPiece);
    best.positions = disc.positions;  // the caller's coordinates (plus seam copies)
    r.method = pieceMethod;
    r.distortion = pieceDistortion;
    decision << methodName(pieceMethod) << (refinedPiece ? " refined by ARAP rounds" : "") << ": L2 stretch "
             << pieceDistortion.l2_stretch;
    if (haveAtlas) {
      decision << ", within " << opts.one_piece_preference << "x of the atlas's " << atlasDistortion.l2_stretch
               << " (one piece has no seams)";
    } else {
      decision << ", the least of the valid one-piece maps";
    }
  }
  if (opts.method == Method::Auto) r.decision = decision.str();
  r.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  if (r.distortion.l2_stretch > opts.max_stretch && !opts.accept_over_stretch) {
    // Methods the budget left out may have done better: say so, and how to let them run.
    std::string skipped;
    for (const MethodTrial& t : r.trials) {
      if (!t.ran && t.note.find("budget") != std::string::npos)
        skipped += (skipped.empty() ? "" : ", ") + std::string(methodName(t.method));
    }
    std::ostringstream left_out;
    if (!skipped.empty())
      left_out << "; the --budget of " << opts.budget_seconds << " s left out " << skipped
               << ", which a larger budget would try";
    throw makeError(what, ": the best map (", methodName(r.method), ") has L2 stretch ", r.distortion.l2_stretch,
                    ", above --max-stretch ", opts.max_stretch,
                    "; raise it or pass --accept-stretch to keep the map anyway (tried ", trialSummary(r), ")",
                    left_out.str());
  }
  return best;
}

}  // namespace shanshui::param

// CGAL's fixed-border parameterizers (one translation unit: ~1 min and ~2 GB to compile).
#include <algorithm>
#include <array>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <mutex>
#include <sstream>
#include <string>

#include <CGAL/Surface_mesh_parameterization/Barycentric_mapping_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/Circular_border_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/Discrete_conformal_map_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/Iterative_authalic_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/Mean_value_coordinates_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/Square_border_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/parameterize.h>
#include <Eigen/Eigenvalues>

#include "cgal_methods.h"
#include "cgal_surface_mesh.h"

namespace shanshui::param::detail {
namespace {

namespace SMP = CGAL::Surface_mesh_parameterization;
using Circle = SMP::Circular_border_arc_length_parameterizer_3<SurfaceMesh>;
using Square = SMP::Square_border_arc_length_parameterizer_3<SurfaceMesh>;

// CGAL 5.5's iterative authalic parameterizer hard-codes DEBUG_L0 1: every iteration prints
// to std::cout and writes "last_solve.off" into the working directory, which would clobber a
// user's file of that name. The macro is defined unconditionally inside the header, so it
// cannot be switched off from here; instead the solve runs with std::cout captured and the
// working directory moved to a private scratch directory, removed afterwards. Both are
// process-wide, so calls are serialised; nothing else in the tools opens relative paths
// while a parameterization runs.
class QuietCgalDebugOutput {
 public:
  QuietCgalDebugOutput() : lock_(mutex()), saved_cout_(std::cout.rdbuf(sink_.rdbuf())) {
    namespace fs = std::filesystem;
    std::error_code ec;
    saved_dir_ = fs::current_path(ec);
    if (ec) return;  // no working directory: CGAL's write fails and nothing is written
    std::string pattern = (fs::temp_directory_path(ec) / "shanshui-param-XXXXXX").string();
    if (ec || ::mkdtemp(pattern.data()) == nullptr) return;
    scratch_ = pattern;
    fs::current_path(scratch_, ec);
    if (ec) {
      fs::remove_all(scratch_, ec);
      scratch_.clear();
    }
  }
  ~QuietCgalDebugOutput() {
    std::cout.rdbuf(saved_cout_);
    if (scratch_.empty()) return;
    std::error_code ec;
    std::filesystem::current_path(saved_dir_, ec);
    std::filesystem::remove_all(scratch_, ec);
  }
  QuietCgalDebugOutput(const QuietCgalDebugOutput&) = delete;
  QuietCgalDebugOutput& operator=(const QuietCgalDebugOutput&) = delete;

 private:
  static std::mutex& mutex() {
    static std::mutex m;
    return m;
  }
  std::lock_guard<std::mutex> lock_;
  std::ostringstream sink_;
  std::streambuf* saved_cout_;
  std::filesystem::path saved_dir_, scratch_;
};

// Four border vertices for the square's corners: the extremes of the border in the four
// diagonal directions of its principal plane, in border order. (CGAL's automatic corners
// produced zero-area faces on grid terrain, SPEC.md section 5.)
Square squareBorder(const SurfaceMesh& sm, HalfedgeIndex border) {
  std::vector<VertexIndex> loop;
  for (HalfedgeIndex h : CGAL::halfedges_around_face(border, sm)) loop.push_back(sm.source(h));
  if (loop.size() < 4) throw makeError("square border: the border has ", loop.size(), " vertices, needs 4");
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (VertexIndex v : loop) mean += Eigen::Vector3d(sm.point(v).x(), sm.point(v).y(), sm.point(v).z());
  mean /= static_cast<double>(loop.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (VertexIndex v : loop) {
    const Eigen::Vector3d d = Eigen::Vector3d(sm.point(v).x(), sm.point(v).y(), sm.point(v).z()) - mean;
    cov += d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(cov);
  const Eigen::Vector3d a = eigen.eigenvectors().col(2), b = eigen.eigenvectors().col(1);
  std::array<std::size_t, 4> corner{};
  const double signs[4][2] = {{1, 1}, {-1, 1}, {-1, -1}, {1, -1}};
  for (int k = 0; k < 4; ++k) {
    double best = -std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const Eigen::Vector3d d =
          Eigen::Vector3d(sm.point(loop[i]).x(), sm.point(loop[i]).y(), sm.point(loop[i]).z()) - mean;
      const double score = signs[k][0] * d.dot(a) + signs[k][1] * d.dot(b);
      if (score > best) {
        best = score;
        corner[k] = i;
      }
    }
  }
  std::sort(corner.begin(), corner.end());
  if (std::adjacent_find(corner.begin(), corner.end()) != corner.end()) {
    throw makeError("square border: could not find four distinct corners on the border; use --border circle");
  }
  return Square(loop[corner[0]], loop[corner[1]], loop[corner[2]], loop[corner[3]]);
}

template <typename BorderParameterizer>
SMP::Error_code run(SurfaceMesh& sm, HalfedgeIndex border, UvMap uv, Method method, const BorderParameterizer& bp,
                    int authalicIterations) {
  switch (method) {
    case Method::Mvc:
      return SMP::parameterize(sm, SMP::Mean_value_coordinates_parameterizer_3<SurfaceMesh, BorderParameterizer>(bp),
                               border, uv);
    case Method::Dcm:
      return SMP::parameterize(sm, SMP::Discrete_conformal_map_parameterizer_3<SurfaceMesh, BorderParameterizer>(bp),
                               border, uv);
    case Method::Tutte:
      return SMP::parameterize(sm, SMP::Barycentric_mapping_parameterizer_3<SurfaceMesh, BorderParameterizer>(bp),
                               border, uv);
    case Method::Authalic: {
      const QuietCgalDebugOutput quiet;
      SMP::Iterative_authalic_parameterizer_3<SurfaceMesh, BorderParameterizer> p(bp);
      return p.parameterize(sm, border, uv, static_cast<unsigned>(authalicIterations));
    }
    default:
      break;
  }
  throw makeError("method '", methodName(method), "' is not a fixed-border method");
}

}  // namespace

std::vector<glm::dvec2> fixedBorderUvs(const mesh::Mesh& m, Method method, Border border, int authalicIterations) {
  SurfaceMesh sm = toSurfaceMesh(m);
  const HalfedgeIndex bhd = longestBorder(sm);
  UvMap uv = sm.add_property_map<VertexIndex, Kernel::Point_2>("v:uv").first;
  const SMP::Error_code status = border == Border::Square
                                     ? run(sm, bhd, uv, method, squareBorder(sm, bhd), authalicIterations)
                                     : run(sm, bhd, uv, method, Circle(), authalicIterations);
  if (status != SMP::OK) throw makeError(methodName(method), " failed: ", statusName(status));
  return readUvs(sm, uv);
}

}  // namespace shanshui::param::detail

#include "dbss/encoder/point_distances.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "dbss/encoder/triangle_tree.h"
#include "mesh_geometry.h"

namespace dbss {

using namespace mesh_geometry;

SurfaceDistance points_to_mesh(const std::vector<float>& xyz, const TriangleMesh& m) {
  const TriangleTree tree(m);
  SurfaceDistance out;
  const size_t n = xyz.size() / 3;
  for (size_t i = 0; i < n; ++i) {
    const double p[3] = {xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]};
    const double d = tree.distance(p);
    out.mean += d;
    out.max = std::max(out.max, d);
  }
  if (n) out.mean /= n;
  return out;
}

PointPlane fit_plane(const PointCloud& pc, const uint32_t* indices, size_t count) {
  PointPlane out;
  if (count == 0) return out;
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (size_t j = 0; j < count; ++j) c += Eigen::Vector3d(pc.xyz[3 * indices[j]], pc.xyz[3 * indices[j] + 1], pc.xyz[3 * indices[j] + 2]);
  c /= static_cast<double>(count);
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (size_t j = 0; j < count; ++j) {
    const Eigen::Vector3d d = Eigen::Vector3d(pc.xyz[3 * indices[j]], pc.xyz[3 * indices[j] + 1], pc.xyz[3 * indices[j] + 2]) - c;
    cov += d * d.transpose();
  }
  // The direction of least spread: the eigenvector of the smallest
  // eigenvalue (Eigen sorts them ascending).
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  const Eigen::Vector3d n = eig.eigenvectors().col(0);
  out.point = {c[0], c[1], c[2]};
  out.normal = {n[0], n[1], n[2]};
  const Eigen::Vector3d v = eig.eigenvalues() / static_cast<double>(count);
  out.variance = {v[0], v[1], v[2]};
  return out;
}

SurfaceDistance vertices_to_points_surface(const std::vector<float>& xyz, const PointIndex& index) {
  const PointCloud& pc = index.points();
  SurfaceDistance out;
  const size_t n = xyz.size() / 3;
  uint32_t near[8];
  float d2[8];
  for (size_t i = 0; i < n; ++i) {
    const size_t k = index.nearest_k(&xyz[3 * i], 8, near, d2);
    const PointPlane plane = fit_plane(pc, near, k);
    const Eigen::Vector3d p(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
    const Eigen::Vector3d c(plane.point[0], plane.point[1], plane.point[2]), nrm(plane.normal[0], plane.normal[1], plane.normal[2]);
    const double dist = std::abs((p - c).dot(nrm));
    out.mean += dist;
    out.max = std::max(out.max, dist);
  }
  if (n) out.mean /= n;
  return out;
}

bool inside_mesh(const TriangleMesh& m, const std::array<double, 3>& p) {
  // Sum of signed solid angles (Van Oosterom-Strackee): 4π inside, 0 outside.
  double total = 0;
  for (size_t f = 0; f < m.triangle_count(); ++f) {
    const V3 a = sub(pos(m, m.triangles[3 * f]), p), b = sub(pos(m, m.triangles[3 * f + 1]), p),
             c = sub(pos(m, m.triangles[3 * f + 2]), p);
    const double la = std::sqrt(dot(a, a)), lb = std::sqrt(dot(b, b)), lc = std::sqrt(dot(c, c));
    const double num = dot(a, cross(b, c));
    const double den = la * lb * lc + dot(a, b) * lc + dot(b, c) * la + dot(c, a) * lb;
    total += 2 * std::atan2(num, den);
  }
  return total > 2 * std::numbers::pi;
}

}  // namespace dbss

#include "dbss/encoder/simplify.h"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModAspectRatioT.hh>
#include <OpenMesh/Tools/Decimater/ModNormalFlippingT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>

#include <algorithm>
#include <string>

namespace dbss {

namespace {
struct Traits : public OpenMesh::DefaultTraits {
  typedef OpenMesh::Vec3d Point;
  typedef OpenMesh::Vec3d Normal;
};
using OMesh = OpenMesh::TriMesh_ArrayKernelT<Traits>;
}  // namespace

uint32_t default_control_faces(uint32_t shell_faces, int64_t genus) {
  const int64_t lo = 96 + 64 * std::max<int64_t>(0, genus);
  const int64_t f = std::clamp<int64_t>(shell_faces / 8, lo, std::max<int64_t>(lo, 4000));
  return static_cast<uint32_t>(f & ~int64_t{1});
}

Result<TriangleMesh> simplify_mesh(const TriangleMesh& in, uint32_t target_faces, SimplifyStats* stats) {
  OMesh om;
  std::vector<OMesh::VertexHandle> vh;
  vh.reserve(in.vertex_count());
  for (size_t v = 0; v < in.vertex_count(); ++v)
    vh.push_back(om.add_vertex(OMesh::Point(in.positions[3 * v], in.positions[3 * v + 1], in.positions[3 * v + 2])));
  for (size_t f = 0; f < in.triangle_count(); ++f) {
    const auto fh = om.add_face(vh[in.triangles[3 * f]], vh[in.triangles[3 * f + 1]], vh[in.triangles[3 * f + 2]]);
    if (!fh.is_valid()) return Status(ErrorCode::bad_mesh, "simplify: triangle " + std::to_string(f) + " is not manifold");
  }
  om.request_face_normals();
  om.update_face_normals();

  OpenMesh::Decimater::DecimaterT<OMesh> decimater(om);
  OpenMesh::Decimater::ModQuadricT<OMesh>::Handle quadric;
  OpenMesh::Decimater::ModNormalFlippingT<OMesh>::Handle flipping;
  OpenMesh::Decimater::ModAspectRatioT<OMesh>::Handle aspect;
  decimater.add(quadric);
  decimater.add(flipping);
  decimater.add(aspect);
  decimater.module(quadric).unset_max_err();
  decimater.module(flipping).set_max_normal_deviation(60.0);
  decimater.module(aspect).set_aspect_ratio(10.0f);
  if (!decimater.initialize()) return Status(ErrorCode::internal, "simplify: OpenMesh decimater did not initialize");
  decimater.decimate_to_faces(0, target_faces);
  om.garbage_collection();

  TriangleMesh out;
  out.positions.reserve(om.n_vertices() * 3);
  for (const auto v : om.vertices()) {
    const auto p = om.point(v);
    for (int a = 0; a < 3; ++a) out.positions.push_back(static_cast<float>(p[a]));
  }
  out.triangles.reserve(om.n_faces() * 3);
  for (const auto f : om.faces())
    for (const auto v : om.fv_range(f)) out.triangles.push_back(static_cast<uint32_t>(v.idx()));
  if (stats) {
    stats->faces_before = static_cast<uint32_t>(in.triangle_count());
    stats->faces_after = static_cast<uint32_t>(out.triangle_count());
  }
  return out;
}

}  // namespace dbss

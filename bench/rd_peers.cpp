// CGAL reconstructions for bench/rd_bench, kept in their own translation
// unit: CGAL's headers are slow to compile and noisy under -Wall.
#include "rd_peers.h"

#include <array>
#include <chrono>
#include <cstdint>
#include <utility>

#include <CGAL/Advancing_front_surface_reconstruction.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Random.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/compute_average_spacing.h>
#include <CGAL/jet_estimate_normals.h>
#include <CGAL/mst_orient_normals.h>
#include <CGAL/poisson_surface_reconstruction.h>
#include <CGAL/property_map.h>

namespace dbss::bench {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Vector = Kernel::Vector_3;
using Clock = std::chrono::steady_clock;

std::vector<Point> to_points(const std::vector<double>& xyz) {
  std::vector<Point> p;
  p.reserve(xyz.size() / 3);
  for (size_t i = 0; i + 2 < xyz.size(); i += 3) p.emplace_back(xyz[i], xyz[i + 1], xyz[i + 2]);
  return p;
}

double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// CGAL's default random generator (the Poisson surface mesher's initial
// points among others) is seeded from the clock; a fixed seed before each
// reconstruction makes a run repeat the previous one exactly.
void fix_cgal_seed() { CGAL::get_default_random() = CGAL::Random(0); }

}  // namespace

Reconstruction advancing_front(const std::vector<double>& xyz) {
  const auto t0 = Clock::now();
  fix_cgal_seed();
  const std::vector<Point> points = to_points(xyz);
  std::vector<std::array<std::size_t, 3>> facets;
  CGAL::advancing_front_surface_reconstruction(points.begin(), points.end(), std::back_inserter(facets));
  Reconstruction r;
  // Facets index the input points; points no facet uses are left out, so
  // the vertex count is the mesh's own.
  std::vector<uint32_t> renumber(points.size(), UINT32_MAX);
  for (const auto& f : facets)
    for (std::size_t i : f) {
      if (renumber[i] == UINT32_MAX) {
        renumber[i] = static_cast<uint32_t>(r.mesh.vertex_count());
        const Point& p = points[i];
        r.mesh.positions.insert(r.mesh.positions.end(),
                                {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())});
      }
      r.mesh.triangles.push_back(renumber[i]);
    }
  if (facets.empty()) r.failure = "no facets", r.mesh = {};
  r.seconds = since(t0);
  return r;
}

Reconstruction poisson(const std::vector<double>& xyz, unsigned neighbours) {
  const auto t0 = Clock::now();
  fix_cgal_seed();
  using PointNormal = std::pair<Point, Vector>;
  std::vector<PointNormal> pn;
  for (const Point& p : to_points(xyz)) pn.emplace_back(p, Vector(0, 0, 0));
  const auto params = CGAL::parameters::point_map(CGAL::First_of_pair_property_map<PointNormal>())
                          .normal_map(CGAL::Second_of_pair_property_map<PointNormal>());
  CGAL::jet_estimate_normals<CGAL::Sequential_tag>(pn, neighbours, params);
  pn.erase(CGAL::mst_orient_normals(pn, neighbours, params), pn.end());
  Reconstruction r;
  if (pn.size() < 4) {
    r.failure = "normals could not be oriented";
    r.seconds = since(t0);
    return r;
  }
  const double spacing = CGAL::compute_average_spacing<CGAL::Sequential_tag>(
      pn, 6, CGAL::parameters::point_map(CGAL::First_of_pair_property_map<PointNormal>()));
  CGAL::Surface_mesh<Point> out;
  if (!CGAL::poisson_surface_reconstruction_delaunay(pn.begin(), pn.end(), CGAL::First_of_pair_property_map<PointNormal>(),
                                                     CGAL::Second_of_pair_property_map<PointNormal>(), out, spacing)) {
    r.failure = "Poisson solver failed";
    r.seconds = since(t0);
    return r;
  }
  // A freshly built Surface_mesh has no removed elements, so its vertex
  // indices run 0..n-1.
  for (auto v : out.vertices()) {
    const Point& p = out.point(v);
    r.mesh.positions.insert(r.mesh.positions.end(),
                            {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())});
  }
  for (auto f : out.faces()) {
    std::vector<uint32_t> ring;
    for (auto v : CGAL::vertices_around_face(out.halfedge(f), out)) ring.push_back(static_cast<uint32_t>(v.idx()));
    for (size_t k = 1; k + 1 < ring.size(); ++k) r.mesh.triangles.insert(r.mesh.triangles.end(), {ring[0], ring[k], ring[k + 1]});
  }
  if (r.mesh.triangles.empty()) r.failure = "empty surface", r.mesh = {};
  r.seconds = since(t0);
  return r;
}

}  // namespace dbss::bench

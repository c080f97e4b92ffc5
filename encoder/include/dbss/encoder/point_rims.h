// Where a scan's points end: the rims of the openings in a point cloud,
// found from the points alone (not from any surface made of them), and the
// pairs of rims that look like the two ends of a tube the scan cut through.
// The self-check uses them to tell whether a closed surface joined those
// ends or capped them: a capped pair may be a lost handle, which no figure
// of the surface itself shows (the carving can cap the ends before any
// hole reaches the bridging stage).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "dbss/decoder/mesh.h"
#include "dbss/encoder/point_index.h"
#include "dbss/encoder/triangle_tree.h"

namespace dbss {

struct PointRim {
  std::array<double, 3> centre{};
  // Unit normal of the rim's least-squares plane, pointing away from the
  // opening (into the scanned surface the rim bounds).
  std::array<double, 3> axis{};
  double radius = 0;  // mean distance of the rim's points from the centre
  // The radius of the tube the rim ends, if it ends one: the rim's points'
  // mean distance from the line through its centre along the direction
  // its points' normals are all square to (the tube's).  A cut that crosses
  // a tube of radius r obliquely leaves a rim r by r / sin(angle) in size,
  // whose mean radius overstates the tube.
  double tube_radius = 0;
  // Mean |cos| between the points' surface normals along the rim and the
  // axis: near 0 where the rim cuts across a tube's wall, near 1 round a
  // hole in a wall.
  double wall = 0;
  size_t points = 0;  // boundary points on the rim (of those examined)
  int sectors = 0;    // of 12 sectors of 30 degrees round the axis, those holding its points
};

// How strict find_point_rims is.  The defaults find the rims the encoder
// joins tubes between; the self-check also looks with looser ones
// (scan_check.cpp), where a sparse scan's rim has wider gaps (fewer sectors
// hold points) or breaks into groups of a few boundary points.
struct RimOptions {
  size_t min_points = 8;  // fewest boundary points a rim is made of
  int min_sectors = 8;    // of 12 sectors of 30 degrees round its axis, fewest that hold its points
  double link = 2;        // boundary points closer than this many neighbourhood radii are one rim
};

// A cloud's boundary points (see find_point_rims), kept so that several
// RimOptions can link the same points without finding them again: finding
// them (a neighbour search and a plane fit per point) is the costly part,
// and it does not depend on the options.
struct RimPoints {
  PointCloud edge;                          // the boundary points
  std::vector<std::array<double, 3>> normal;  // each one's surface normal
  std::vector<std::array<double, 3>> into;    // the empty sector's direction, in the tangent plane
  std::vector<double> reach;                  // the radius of each one's neighbourhood
};
RimPoints find_rim_points(const PointIndex& index, size_t max_points = size_t{1} << 16);
std::vector<PointRim> link_rims(const RimPoints& points, const RimOptions& options = {});

// The closed rims of openings in the points: boundary points (a point whose
// nearest neighbours, seen in its tangent plane, leave a wide empty sector)
// linked into groups that run most of the way round their centre.  A cloud
// of more than `max_points` points is judged by every ceil(n / max_points)-th
// of them (in the cloud's order) as a cloud of its own, so the cost is
// bounded on any cloud.  Deterministic for a given point order.
std::vector<PointRim> find_point_rims(const PointIndex& index, size_t max_points = size_t{1} << 16,
                                      const RimOptions& options = {});

// Pairs of rims (indices into `rims`) that look like a tube's two cut ends:
// sizes within a factor of two, a gap under six times the larger radius,
// walls along the axes (the two rims' mean PointRim::wall under
// `max_wall`), and at least one rim facing the other across the gap (as
// hole_bridge.h's doubtful pairs).
constexpr double kTubeEndMaxWall = 0.55;
std::vector<std::pair<size_t, size_t>> tube_end_pairs(const std::vector<PointRim>& rims,
                                                      double max_wall = kTubeEndMaxWall);

// Whether a pair of rims from tube_end_pairs is held to the stricter rule
// the self-check's looser rims (RimOptions::min_sectors 7) must meet: each
// rim faces the other across the gap (tube_end_pairs asks it of one), and
// their tube radii agree within a factor of `same_tube` (both ends of one
// cut tube).  A sparse rim is often an arc of a band's side, not a cut
// tube's end.
// The default least ratio of the two ends' tube radii.  On the hole sweep
// (scan_bench --hole-sweep, 4,000 and 8,000 points) the loose pairs of a
// tube the surface capped have 0.87 and 0.91; a false pair, an arc of a
// band round 70 degrees of a tube and the end of another, 0.57.
constexpr double kSameTube = 0.75;
bool rims_face_as_one_tube(const PointRim& a, const PointRim& b, double same_tube = kSameTube);

// Whether a closed, outward-oriented surface joins the two rims of a pair:
// the middle of the gap between them (on the chord and on the Hermite curve
// a bridge would follow) is inside the surface.  A capped pair leaves it
// outside, in the gap.
bool surface_joins(const TriangleMesh& closed_surface, const PointRim& a, const PointRim& b);

// How far the middle of the gap between two rims lies from a surface, in
// the larger of their tube radii: the lesser distance of the two places
// surface_joins tests.  Where a scan missed a band round a tube and the
// surface capped both ends, the gap is empty space a tube's radius or more
// from any surface; where the two "rims" are arcs of one hole's edge and
// the surface bridged it, the gap's middle lies on or near the bridge.
double gap_clearance(const TriangleTree& surface, const PointRim& a, const PointRim& b);

}  // namespace dbss

// Where a clean cloud lies on a flat facet around the line, the facet
// itself: the line's hit on the local Delaunay triangle of the points, taken
// only when enough of the points around it lie on that triangle's plane.
//
// Why: the true meshes of the rd_bench shapes are faceted at the points'
// scale (the eight's 634 triangles meet at 15-33 degrees, edges 11 point
// spacings long).  The quadric fit (surface_fit.h) over the 24 nearest
// points spans about 2.7 spacings, so it rounds every bend over that width;
// advancing front, which interpolates the points, is exact from a spacing
// off the bends (bench/floor_probe --regions, bench/rd_bench.md twelfth and
// thirteenth sessions).  Where the points around the line are coplanar, the
// triangle through three of them is the surface, exactly; where they are
// not (a bend inside the triangle, or any curved surface) the fit stays.
// Points that lie on two lines (two rows of a grid-sampled cylinder) do not
// count as a plane.
#pragma once

#include "dbss/encoder/point_index.h"

namespace dbss {

// The points searched around the foot, and how many of them must lie on
// the triangle's plane (within kFacetFlatness of `radius`) for the triangle
// to count as a facet.  Measured (floor_probe, eight, 30k points, seed 1,
// L5 against the truth; before 1.033e-4): 6 of 16 within 1e-3: 9.15e-5;
// within 1e-4: 9.26e-5 (kept: on the unit sphere at 20k points, 1e-3 let 9
// of 400 lines take a chord, 1e-4 none; a flat facet's points are on its
// plane to float rounding); 9 of 16: 9.41e-5; 4 of 16: 9.39e-5 with 5%
// more bytes; all of the 10 nearest: 1.029e-4 (too few facets pass).  The
// Delaunay triangle without the flatness test: 1.20e-4 (a chord across a
// bend is farther than the fit's rounding of it).
inline constexpr size_t kFacetPoints = 16;
inline constexpr int kFacetSupport = 6;
inline constexpr double kFacetFlatness = 1e-4;

// How the triangles are searched: `pruned` skips only triangles that
// provably fail (facet_hit.cpp); `all` tries every one of the C(16, 3), the
// reference the tests compare `pruned` with.  Both give the same t.
enum class FacetSearch { pruned, all };

// p: the odd vertex; n: its unit normal; t0: the fitted height along n
// (the sheet); radius: the fit's neighbourhood radius.  On success t is the
// line's hit on the facet, within half the radius of t0.
bool facet_hit(const PointIndex& index, const double p[3], const double n[3], double t0, double radius, double& t,
               FacetSearch search = FacetSearch::pruned);

}  // namespace dbss

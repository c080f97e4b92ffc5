// Where Draco's position grid puts the control vertices (point path).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "dbss/decoder/mesh.h"

namespace dbss {

struct ControlRounding {
  size_t vertices = 0;        // vertices placed on a grid point of the encoder's choosing
  double nearest_normal = 0;  // mean |offset along the vertex normal| of plain rounding (model units)
  double chosen_normal = 0;   // the same for the grid points chosen
  double grid = 0;            // the grid's spacing (model units)
  size_t merged = 0;          // edges whose ends met on one grid point and went back to plain rounding
};

// How far (in grid spacings) a vertex may slide along its surface to reach
// a grid point nearer the surface.
inline constexpr double kRoundingSlide = 1.5;

// Moves each vertex of `mesh` onto a point of the grid Draco quantizes
// positions to at `bits` (the mesh's per-axis minimum, (2^bits - 1) steps
// over its largest extent), chosen, among the grid points within
// kRoundingSlide spacings of the vertex along its surface (the plane normal
// to its area-weighted normal) and two spacings of its nearest grid point,
// as the one nearest that plane.  Draco then keeps these positions as
// they are.  Why: a control vertex is an even vertex of every level and
// never moves again, so its offset from the surface stays in every level
// (the odd vertices round it are sampled from the points after it is
// rounded, and take the bump up), while a slide along the surface only
// reparametrizes it.  Plain rounding leaves an offset of about 0.23 grid
// spacings along the normal on average; the chosen point about a tenth of
// that, so the grid can be 2-3 bits coarser for the same offset.  The
// vertices holding the mesh's minimum on an axis keep that coordinate (the
// grid's origin stays where Draco puts it), and no vertex leaves the
// grid's range.  Vertices without a normal round as Draco would, and so do
// the vertices `fixed` marks (non-zero; a mesh's rim, which must not slide
// across itself), placed on their nearest grid point here so that the
// guard against two ends of an edge on one point sees where they end up.
ControlRounding round_along_surface(TriangleMesh& mesh, int bits, const std::vector<uint8_t>* fixed = nullptr);

}  // namespace dbss

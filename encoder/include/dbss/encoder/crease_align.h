// A control mesh whose edges follow the surface's feature lines: control
// vertices moved onto the lines (and corners) the points show around them,
// then edges flipped so that each line runs along a chain of control edges.
// The crease tags (creases.h) only help where such chains exist: an
// isolated tagged edge has darts at both ends and the butterfly rounds the
// feature on either side of it.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "dbss/decoder/mesh.h"
#include "dbss/encoder/creases.h"
#include "dbss/encoder/point_index.h"

namespace dbss {

struct AlignStats {
  size_t line_vertices = 0;    // vertices whose points show two planes
  size_t corner_vertices = 0;  // ... three planes
  size_t snapped = 0;          // vertices moved onto a line or corner
  size_t flips = 0;            // edges flipped to join two vertices of one line
  size_t valence_flips = 0;    // flat edges beside a line flipped toward valence 6
  size_t splits = 0;           // edges split where a line crosses them
  size_t collapses = 0;        // vertices beside a line merged into their neighbour on it
  size_t relaxed = 0;          // moves of flat-face vertices towards their neighbours' mean, in the face
};

// For each vertex of `mesh` (an oriented manifold, closed or open), the
// points within 0.6 of its mean edge length are split into two (or three)
// planar groups by their normals; when the planes meet at more than
// options.angle_degrees and each group is flat (options.flatness), the
// vertex moves onto the planes' line (or their common point) if that is
// within a third of its shortest edge and no triangle turns over or
// becomes a sliver; with options.gap_snaps, a line vertex refused so where
// its line's chain stops at it, and goes on within three of its edges, is
// tried again with a lower sliver floor.  With options.collapse, a vertex whose move was refused
// is merged into its neighbour on the same line when the collapse keeps the
// mesh a manifold (link condition) and its triangles unturned.  With
// options.relax (and a vertex moved), the vertices of flat faces move in
// their face's plane towards their neighbours' mean (the surface is the
// same, the triangles beside a line more even).  Then edges whose quad
// joins two vertices of the same line, along the line, are flipped to that
// diagonal.  Topology (genus,
// boundary) is unchanged.  `chains` (may be null) gets the interior edges
// (u < w, sorted) joining two moved vertices of one line along it: the
// crease edges; `corners` (may be null) the vertices moved onto a corner.
// With options.split, where a line stops short of the next vertex on it,
// the edges it crosses are split at the line (new vertices at the end of
// mesh.positions), at most a tenth of the vertex count.  Does nothing when
// options.angle_degrees <= 0.  Deterministic (fixed visiting order).
void align_to_features(TriangleMesh& mesh, const PointIndex& points, const CreaseOptions& options,
                       AlignStats* stats = nullptr, std::vector<std::array<uint32_t, 2>>* chains = nullptr,
                       std::vector<uint32_t>* corners = nullptr);

// A unit normal per point (3 floats each, sign arbitrary): the plane most of
// its 12 nearest points lie on, not their least-squares blend, so a point
// next to a feature takes its own side's normal.  For one-sided sampling
// (surface_fit.h's PointSides).  Split over `threads` (a piece per ten
// thousand points at most); the same floats on any number of them.
std::vector<float> estimate_point_normals(const PointIndex& points, unsigned threads = 1);

}  // namespace dbss

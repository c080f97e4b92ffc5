// Sharp features of the surface from the points: which control-mesh edges
// are creases (format 1.1 tags, spec/dbss-format.md section 10a), and their
// vertices snapped onto the feature lines before sampling.
#pragma once

#include <cstddef>
#include <cstdint>

#include "dbss/decoder/mesh.h"
#include "dbss/encoder/point_index.h"
#include "dbss/format/container.h"

namespace dbss {

struct CreaseOptions {
  // Smallest angle between the two sides' planes, degrees; <= 0: off (no
  // tag is found and the mesh is not touched, so the file is a 1.0 file).
  // Off by default: measured (bench/crease_bench.md, eleventh session), the
  // machined shapes' error no longer rises with level (but for the roof at
  // one seed of three), yet a torus gets a false crease at two seeds of
  // three and scanned smooth shapes several (bunny00 70-89 edges, armadillo
  // 5-16, knot1 1-4), and a tagged file also pays the CREA bitmap (about
  // 900 bytes) and keeps the step's Draco bits, not rounded along the
  // surface: level 3 11-51% more bytes there (bunny00 40% more error).
  // The library keeps it off; the commands and the Python binding turn it
  // on at 30 degrees (tools/encode_options.h, kCommandCreaseAngle), since
  // the quadric test, the lone-run test and min_share leave smooth shapes
  // with no tag (thirteenth session).
  double angle_degrees = 0;
  // Each side's RMS distance from its plane, relative to the neighbourhood's
  // radius, must stay under this: a crease has flat sides near it, a smooth
  // bend of the same angle does not (its halves deviate by about angle/16).
  double flatness = 0.02;
  size_t min_side_points = 8;  // per side, else the edge is not a crease
  // A crease only where the best single quadric height field through the
  // edge's points (six coefficients, over the plane of its two control
  // triangles) fits them at least this many times worse, RMS, than its two
  // sides' planes (six coefficients too); the chains the alignment tags are
  // held to it as well.  A curved smooth sheet (a torus, a scan's ear) can
  // pass for two planes at any angle; a quadric follows it.  <= 0: no test.
  // 8: measured (bench/crease_bench.md, twelfth session; 40,000 points,
  // seeds 1-3), the smallest of 2, 3, 4, 5, 6, 8 under which bunny00,
  // armadillo, knot1 and the torus keep no candidate edge (bunny00 at 2:
  // 15-16 of 61-83; at 5: 0-3); on the cube, roof and cylinder 90-100% of
  // the candidates pass it, on the fandisk and anchor 80-86%.
  double smooth_ratio = 8;
  // The feature runs along the edge: the planes' line within acos(parallel)
  // of it, and each end within reach * its length of both planes.
  double parallel = 0.94;  // cos 20 degrees
  double reach = 0.3;
  // Split the edges a feature line crosses where its chain stops short
  // (crease_align.h).  Off: measured (bench/crease_bench.md) it joined few
  // chains (14 splits on the cube, 109 on the fandisk), added 7% to the
  // fandisk's control-mesh bytes for no lower error, and took the anchor's
  // level-3 error from 1.67e-4 to 2.23e-4 of the diagonal (Hausdorff 3.0%
  // to 4.6%).
  bool split = false;
  // Merge a vertex beside a line, whose move onto it was refused, into its
  // neighbour on the line (crease_align.h).  Off: measured
  // (bench/crease_bench.md, fifth session) it halves the cube's darts (110
  // -> 58) but raises the anchor's level-1 error 4.2e-4 -> 6.4e-4 and its
  // level 3 3.8e-4 -> 4.6e-4 (curved feature lines), and the cube's level 1
  // without the wedge sampling too.
  bool collapse = false;
  // Sample next to a crease from the two sides' planes (sampling.cpp's
  // wedge), not from a surface fit over both.
  bool wedge = true;
  // The wedge only within reach of a tagged crease edge (crease_lines.h):
  // else a smooth region curved tightly enough (radius about 1.5 times the
  // wedge's 32-point neighbourhood) can pass for two planes.
  bool wedge_gate = true;
  // One-sided sampling (the points whose normals agree with the line's)
  // only where the fit's own points do not all agree; where they do, a
  // clean cloud's sample, with the tight kernel and the facet hit
  // (sampling.cpp).  Off (the default): every sample of a tagged file
  // one-sided, with the narrow kernel.  Measured (bench/crease_bench.md,
  // fourteenth session): L3 error -4% to +1.6% on ten parts, but L3
  // Hausdorff up on the cylinder (0.99 -> 1.11%, over the 1% bound), the
  // rotor and the turbine, so it stays off until the rim vertex it no longer
  // pulls back is understood.
  bool clean_away = false;
  // Clamp a tagged control mesh's vertices onto the points' axis-plane
  // faces at their bounding box's sides before Draco rounds them
  // (encode.cpp clamp_to_box_faces): a crease vertex snapped past such a
  // face shifts Draco's grid off every vertex of those faces, an offset no
  // level can store.  Measured (bench/crease_bench.md, fifteenth session,
  // 40k points, seeds 1-3): level-3 error cube -5/-52/-74%, roof
  // -32/-32/-12%, cylinder -3/-2/-6%, but the roof's level 3 then rises over
  // level 2 at seed 2 (x1.020: the faces' one-sided level-3 samples, masked
  // before by the grid's offset) and the cylinder's level-3 Hausdorff at
  // seed 1 moves 0.99 -> 1.13%, so it is off until those are mended.
  bool clamp_to_points = false;
  // Relax the flat faces' vertices in their plane after the alignment
  // (crease_align.h).  It once raised the fandisk's level 1 (3.1e-4 ->
  // 4.6e-4): not the relaxation itself but the sampler, which on the
  // fandisk's thin flange took triangles bridging its two faces; with the
  // sampler keeping to one sheet (sampling.cpp) it lowers level 1 on all
  // five shapes of bench/crease_bench.md (seventh session).
  bool relax = true;
  // The relaxation also moves vertices that see a line in their points but
  // were not moved onto it (too far, or refused), when their triangles lie
  // in one plane: QEM leaves them beside the line with a ring of a few short
  // edges towards it and a few long ones across the face, and the
  // butterfly's extraordinary rule there puts odd vertices past the line in
  // the face's plane (the cube: valence 8, neighbours 0.07-1.7 away, an odd
  // vertex 0.128 outside, its Hausdorff distance).  Only with `relax`, and
  // only fans flat within 0.1 degree.  Alone it raised the fandisk's level 3
  // 9% (eighth session, one seed); with valence_flips, over three sampling
  // seeds, level 3's error falls on the cube, roof and fandisk
  // (bench/crease_bench.md, ninth session).
  bool relax_beside_lines = true;
  // Flip the edges of flat faces beside a line toward valence 6 (a vertex
  // on the line counts its triangles on that face's side, regular 3)
  // (crease_align.cpp 3b): the surface is unchanged, the butterfly's
  // stencils next to the line more regular.
  bool valence_flips = true;
  // Relax the flat faces once more after those flips (only with `relax`).
  bool relax_after_flips = true;
  // No tag on an edge whose two control triangles lie within 3 degrees of
  // one plane (creases.cpp): the feature is beside it, not along it (the
  // points within 0.6 of a short edge next to a line see both sides).  Off:
  // it brings the tags near the truth (the cube: 76 -> 32 darts, 20 -> 10
  // corners, length 8.52 -> 6.39 against 6.93 true, in diagonals) but level
  // 3's error rose on the cylinder (+13% against +6%) and fandisk (-4%
  // against -9%) at seed 1 (bench/crease_bench.md, ninth session).
  bool untag_flat = false;
  // Tag as corners the smooth control vertices (no crease edge) of valence
  // other than 6 whose triangles lie within flat_fan_degrees of one plane,
  // where the extraordinary rule puts a stencil point of their edges over a
  // quarter of the edge from its midpoint and the tag halves that
  // (creases.cpp).  A corner is sharp (decoding.md section 3), so the edges
  // at it take the local eight-point rule instead of the extraordinary
  // rule, whose ring reaches across a lopsided fan: QEM leaves such
  // vertices beside the lines (a few short edges to the line, long ones
  // across the face), and the extraordinary rule put level-1 odd vertices
  // past the line, in the face's plane, where no displacement along the
  // normal brings them back (the roof's level-3 Hausdorff distance, 1.2% of
  // the diagonal at seed 1).  On a flat fan both rules stay in the plane;
  // the tag costs no byte (CREA's vertex map has a bit for every vertex).
  // Only when some edge is a crease.
  bool flat_corners = true;
  double flat_fan_degrees = 1;
  // How a fan is judged flat for flat_corners: every vertex of its ring
  // within sin(flat_fan_degrees) of the fan's mean edge length from the
  // plane of its area-weighted normal (on), not every triangle within
  // flat_fan_degrees of the first one's plane (off).  A neighbour on a line
  // snapped 0.0005 off the face's plane tilts a short triangle by degrees
  // while the fan stays flat where its stencils reach (the fandisk at seed
  // 1: two triangles at 2 and 5 degrees, the level-3 Hausdorff vertex).
  bool flat_fan_fit = true;
  // After choosing the flat_corners tags (each candidate judged with every
  // candidate tagged), judge the chosen ones again with the tags as they
  // end up, untagging any whose worst stencil offset is no longer halved
  // (an edge between a tagged and an untagged candidate is otherwise never
  // measured in its final configuration); up to three rounds.  Off: with
  // the wedge sampler beside lines (sampling.cpp) the check's dropped tags
  // cost more than they save (crease_bench, 3 seeds, level 3, on -> off:
  // cylinder Hausdorff worst 1.14 -> 0.96%, cube 0.79 -> 0.62% with no
  // L2 -> L3 rise, fandisk's L2 -> L3 rise 1.045 -> none; roof worst
  // 0.68 -> 0.75%: bench/crease_bench.md, eleventh session, merged).
  bool flat_fan_check = false;
  // Retry, with a lower quality floor, the move onto its line of a vertex
  // in a gap of the line's chain (crease_align.cpp 2a).
  bool gap_snaps = true;
  // Chain edges too short for their own smooth test, in a lone run of one
  // or two (no chain edge that passed joins it), are tested over their 32
  // nearest points each and untagged unless the quadric fits this many
  // times worse than two planes (creases.cpp, judge_unfit_runs); <= 0:
  // kept untested.  Lower than smooth_ratio: at that width a true crease's
  // sides bend too (the fandisk's short runs 2.7-7.5); bunny00's lone runs,
  // seeds 1-3, measured 0.4-2.05 (bench/crease_bench.md, twelfth session).
  double chain_run_ratio = 2.5;
  // Tags are kept only when the crease edges are at least this share of
  // the control mesh's edges; fewer, and the mesh is given back unaligned
  // with no tag (the file creases off writes).  A tagged file gives up
  // rounding the control mesh along the surface and pays the CREA bitmap
  // (about 700 bytes) whatever the tags' number: with one or two tagged
  // edges (bunny00, camel, cow at 30,000 points) level 3 cost 16-17% more
  // bytes, for up to 28% more error.  Machined parts measured 2-12% (rotor
  // 0.9%), the smooth shapes' stray tags 0.03-0.05%
  // (bench/crease_bench.md, thirteenth session).  <= 0: any tag is kept.
  double min_share = 0.005;
  // Tags are kept only when their darts (crease ends that are not corners)
  // are at most this share of the crease edges; more, and the tags are in
  // pieces: features the control mesh does not resolve (couplingdown's
  // narrow chamfers and thin rims, the rotor's blades), whose tags made the
  // file worse than none.  The mesh is given back unaligned with no tag, as
  // for min_share.  Measured (bench/crease_bench.md, fourteenth session;
  // 40,000 points, seeds 1-2): the fandisk, anchor, part, joint, spool,
  // turbine, cube, cylinder and roof 0.10-0.34; couplingdown 0.66 (level 3
  // +12% error creases on), the rotor 0.77 and 0.47 (at 0.47 level 3 +1.4%
  // error, +4.6% bytes, Hausdorff 1.50 -> 2.56% creases on).  <= 0: no test.
  double max_dart_share = 0.4;
  // A tagged edge u-w whose triangle's third corner c (untagged) lies on
  // the segment u-w is flipped to the other triangle's far corner, c moved
  // onto the segment and the tag moved onto u-c and c-w (crease_slivers.h):
  // the line then runs through c, and c's stencils see it.
  bool sliver_flips = true;
  // An untagged edge under an eighth of the longest edge at its ends is
  // collapsed into one end (crease_short_edges.h): its level-1 stencil
  // point lands edge lengths off it, past the line or off the face.
  bool short_collapses = true;
  // An untagged interior vertex the builder left off the points (a tent
  // outside its own ring, which the projection could not move without
  // turning a triangle over) is moved onto the points' plane
  // (crease_off_points.h): control vertices stay at every level.  On, with
  // the shaping pass before it (40,000 points, seeds 1-3, crease_bench):
  // the cylinder's level-3 Hausdorff distance 0.70 / 0.87 / 0.77% ->
  // 0.77 / 0.59 / 0.74%, the roof's level 3 -4% and -7% at seeds 2-3, no
  // level over the one before on any shape.  (Alone, before the shaping
  // pass, the roof at seed 2 rose x1.004 over level 2 with it, so it was
  // off; bench/crease_bench.md, sixteenth session.)
  bool settle_off_points = true;
  // After those, the shaping pass once more (crease_shape.h): edge flips
  // toward valence 6 and away from slivers, and sliver vertices moved from
  // point to point, with no tagged edge flipped and no vertex on a line or
  // tagged corner moved (issue 16 item 0: the alignment's moves and flips
  // leave slivers and high valences beside the lines).
  bool shape_after_tags = true;
};

struct CreaseStats {
  size_t edges_tested = 0;  // interior edges with enough points
  size_t creases = 0, corners = 0;
  size_t darts = 0;        // vertices where a crease ends (one crease edge)
  size_t gaps_closed = 0;  // edges tagged because they join two crease ends in line
  size_t spurs = 0;        // tags taken back: a dart's edge off a chain
  size_t smooth_rejected = 0;  // edges (chains' too) a single quadric fits nearly as well as two planes (smooth_ratio)
  size_t snapped = 0;      // vertices moved onto a feature line or corner
  size_t clamped_to_points = 0;  // control vertices clamped onto the points' box faces before Draco (CreaseOptions::clamp_to_points)
  double max_snap = 0;     // largest move, model units
  // The control mesh's alignment to the feature lines before the test
  // (crease_align.h): counts of its vertices moved and edges flipped.
  size_t aligned = 0, align_flips = 0, align_valence_flips = 0, align_splits = 0, align_collapses = 0, align_relaxed = 0;
  size_t chain_edges = 0;  // tagged as joining two aligned vertices along their line
  size_t chain_runs_dropped = 0;  // chain edges untagged by the lone-run test (CreaseOptions::chain_run_ratio)
  size_t flat_corners = 0;  // smooth vertices of flat, irregular fans tagged corner (CreaseOptions::flat_corners)
  size_t flat_corners_dropped = 0;  // of those chosen, untagged by the check (CreaseOptions::flat_fan_check)
  size_t too_few_dropped = 0;  // crease edges found but untagged, too few to pay for a tagged file (CreaseOptions::min_share)
  size_t in_pieces_dropped = 0;  // crease edges found but untagged, too many darts among them (CreaseOptions::max_dart_share)
  size_t short_collapses = 0;  // short untagged edges collapsed (CreaseOptions::short_collapses)
  size_t sliver_flips = 0;  // slivers along a tagged line flipped away (CreaseOptions::sliver_flips)
  size_t settled = 0;  // untagged vertices off the points moved onto them (CreaseOptions::settle_off_points)
  // The shaping pass on the tagged mesh (CreaseOptions::shape_after_tags):
  // edges flipped, vertices moved, rounds undone because triangles crossed.
  size_t shape_flips = 0, shape_moves = 0, shape_rounds_undone = 0;
};

// First aligns `mesh` to the feature lines (align_to_features: vertices
// moved onto lines and corners, edges flipped and split along them; the
// chains of edges it leaves along each line are tagged).  Then tests every
// other interior edge of `mesh` (a closed or open manifold control
// mesh): the points within 0.6 edge lengths of its midpoint are split by
// side and fitted by one plane per side; the edge is a crease when the two
// planes meet at more than the angle and both sides are flat; such an edge
// off a chain, with a dart at its other end, is untagged again (a spur:
// the edge of a face beside the feature).  A vertex with three or more
// crease edges, or aligned onto a corner with one, is tagged corner.  The vertices of crease
// edges move to the least-squares point of their sides' planes (onto the
// feature line; to the corner where three planes meet), by at most a third
// of their shortest edge.  A mesh that keeps tags is then cleaned up along
// the lines (sliver_flips, short_collapses) and shaped with the lines held
// (shape_after_tags).  Returns the tags in `mesh`'s canonical edge order
// (empty when none is found or the option is off).
format::Creases find_creases(TriangleMesh& mesh, const PointIndex& points, const CreaseOptions& options,
                             CreaseStats* stats = nullptr);

// `from`'s tags for `to`, the same mesh after a codec renumbered vertices
// and triangles and rounded the positions (Draco): vertices are matched by
// nearest position, edges by their matched ends.  Empty if `from` has none.
format::Creases transfer_creases(const TriangleMesh& from, const format::Creases& tags, const TriangleMesh& to);

}  // namespace dbss

#include "dbss/encoder/scan_check.h"
#include "split_ranges.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <unordered_map>
#include <vector>

#include "dbss/encoder/bare_handles.h"
#include "dbss/encoder/encode.h"
#include "dbss/encoder/point_distances.h"
#include "dbss/encoder/open_surface.h"
#include "dbss/encoder/outliers.h"
#include "dbss/encoder/point_rims.h"
#include "dbss/encoder/shell_mesh.h"
#include "dbss/encoder/triangle_tree.h"

namespace dbss {

namespace {

// Bounds.  Displacements clamp when the control mesh is farther from the
// points than the level's range; a few percent happen at creases, more means
// the surface is not where the points are.
constexpr double kMaxClamped = 0.02;
// Surface with no point within kUncoveredReach spacings: a dense scan leaves
// none; an open scan closed over, or a leak, leaves much.
constexpr double kUncoveredReach = 3;
constexpr double kMaxUncovered = 0.05;
// Points' mean distance to the surface, in median spacings.
constexpr double kMaxDistance = 3;
// The third, finer look for rims (the capped-rims test below): boundary
// points linked over 1.5 neighbourhood radii, rims of at least 6 points in
// at least 5 of the 12 sectors.
RimOptions split_rim_options() {
  RimOptions o;
  o.link = 1.5;
  o.min_sectors = 5;
  o.min_points = 6;
  return o;
}
// Least clearance (gap_clearance, in tube radii) of a split pair the
// surface capped.  On the hole sweeps (scan_bench --hole-sweep --surface
// closed, 4,000 and 8,000 points) the capped split pairs of lost handles
// read 1.34-2.05; those of right rows (arcs of one bridged hole's edge)
// 0.26-0.76.
constexpr double kMinGapClearance = 1.0;
// The fourth look (full_rim_options): the split rims that still run round
// 8 of the 12 sectors, paired with walls up to kFullRimMaxWall (not
// tube_end_pairs' 0.55) when both face each other with tube radii within
// kFullRimSameTube and the gap is kMinGapClearance clear.  On the hole
// sweeps and clean tori (4,000 and 8,000 points, bench/rim_probe) a tube
// cut obliquely round a ring and capped reads walls 0.57, tube radii 0.96
// and clearance 1.46; right rows' full, facing, uncapped pairs of tube
// radii within 0.9 read clearance 0.37-0.42, and those 1.0 or more clear
// have tube radii 0.62-0.70.
RimOptions full_rim_options() {
  RimOptions o = split_rim_options();
  o.min_sectors = RimOptions{}.min_sectors;
  return o;
}
constexpr double kFullRimMaxWall = 0.65;
constexpr double kFullRimSameTube = 0.9;
// Largest level (in triangles) the capped-rims test runs its inside tests on.
constexpr size_t kJoinTestTriangles = size_t{1} << 16;
// Points dropped as outliers before a warning.
constexpr double kMaxDropped = 0.05;

// The points' mean distance to the mesh over at most kDistanceSample of
// them, evenly spread through the input (every point up to that many, so
// smaller scans keep their exact figure; a scanner's order sweeps the
// object, so a stride through it samples all of it).  The figure only
// decides a warning; over all of 10M points it took 20-40 s.  With 2^18
// samples its standard error is about 1/500 of it (distances spread about
// as widely as their mean), far inside the warning's bound of 3 spacings.
constexpr size_t kDistanceSample = size_t{1} << 18;

double sampled_points_to_mesh(const PointCloud& pc, const TriangleMesh& mesh, unsigned threads) {
  const size_t n = pc.size();
  const size_t m = std::min(n, kDistanceSample);
  if (m == 0) return 0;
  const TriangleTree tree(mesh);
  // Each sample's distance written by one thread, summed in sample order
  // after: the same figure on any number of threads.
  std::vector<double> d(m);
  const auto body = [&](size_t from, size_t to) {
    for (size_t s = from; s < to; ++s) {
      const size_t i = m == n ? s : s * n / m;
      const double p[3] = {pc.xyz[3 * i], pc.xyz[3 * i + 1], pc.xyz[3 * i + 2]};
      d[s] = tree.distance(p);
    }
  };
  detail::split_ranges(m, threads, body);
  double sum = 0;
  for (double x : d) sum += x;
  return sum / static_cast<double>(m);
}

// The level the surface's figures (components, uncovered area, clamped
// share, the points' distance) are measured on: the finest level that
// sampled anything.  Past the points' density (dead_zone_steps) a level
// samples nothing and stores only zeros: it is the plain butterfly
// refinement of the one before, the same surface to well within a point
// spacing, at 4 to 64 times the triangles, and its clamped count is 0 by
// construction.  The levels' own stats say which level that is, so the
// count of points the levels used (the scan's, plus any a joined tube
// added) needs no second guess here.  Measured at --levels 6 (30k noisy
// points, rd_bench): the check over the finest level took 77-513 s wall
// under load, more than the levels, in the TriangleTree and the uncovered
// area's nearest-point query per triangle.
size_t measured_level(const Encoding& e) {
  const size_t last = e.levels.positions.size() - 1;
  for (auto it = e.levels.stats.rbegin(); it != e.levels.stats.rend(); ++it)
    if (it->by_triangle + it->by_plane + it->by_nearest > 0 && it->level <= last) return it->level;
  return last;
}

// The stats of level l (none for the control mesh, level 0).
const LevelStats* level_stats(const Encoding& e, size_t l) {
  for (const LevelStats& st : e.levels.stats)
    if (st.level == l) return &st;
  return nullptr;
}

// Mean edge length of level l's mesh (each interior edge counted from both
// of its triangles: a mean, not a sum).
double mean_edge(const Encoding& e, size_t l) {
  const std::vector<float>& p = e.levels.positions[l];
  const std::vector<uint32_t>& t = e.levels.triangles[l];
  double sum = 0;
  for (size_t i = 0; i < t.size(); ++i) {
    const uint32_t a = t[i], b = t[i % 3 == 2 ? i - 2 : i + 1];
    double d2 = 0;
    for (int k = 0; k < 3; ++k) d2 += std::pow(double{p[3 * a + k]} - double{p[3 * b + k]}, 2);
    sum += std::sqrt(d2);
  }
  return t.empty() ? 0 : sum / static_cast<double>(t.size());
}

// The level the clamped share is read from.  A displacement clamps where it
// would move its vertex more than half its edge (sampling.cpp); that is a
// surface far from the points only while half an edge is more than the
// points' own scatter.  On a noisy cloud whose levels refine past that, the
// fit's heights scatter over half an edge by chance: libcgal-demo's
// sphere_20k (noise about half a point spacing) clamps 0.0/0.2/0.9/3.9% at
// levels 2-5 of a closed, one-component sphere 1.0 spacing from its points,
// and was warned of "a hole the carving leaked through".  A leak or a sheet
// closed over clamps at every level, the coarse ones too, so it is still
// seen at the finest level whose half edge is at least the noise.
size_t clamp_level(const Encoding& e, size_t measured) {
  if (!(e.noise > 0)) return measured;
  for (size_t l = measured; l >= 1; --l)
    if (mean_edge(e, l) / 2 >= e.noise) return l;
  return std::min<size_t>(measured, 1);
}

// Each triangle of m cut into four at its edges' midpoints (flat: the
// vertices added lie on m's triangles).
TriangleMesh split_at_midpoints(const TriangleMesh& m) {
  TriangleMesh out;
  out.positions = m.positions;
  std::unordered_map<uint64_t, uint32_t> mid;
  const auto midpoint = [&](uint32_t a, uint32_t b) {
    const uint64_t key = uint64_t{std::min(a, b)} << 32 | std::max(a, b);
    const auto [it, added] = mid.emplace(key, static_cast<uint32_t>(out.positions.size() / 3));
    if (added)
      for (int k = 0; k < 3; ++k) out.positions.push_back(0.5f * (m.positions[3 * a + k] + m.positions[3 * b + k]));
    return it->second;
  };
  for (size_t t = 0; t < m.triangle_count(); ++t) {
    const uint32_t a = m.triangles[3 * t], b = m.triangles[3 * t + 1], c = m.triangles[3 * t + 2];
    const uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
    out.triangles.insert(out.triangles.end(), {a, ab, ca, ab, b, bc, ca, bc, c, ab, bc, ca});
  }
  return out;
}

// Reach, in local spacings, past which a handle's tunnel counts as bare.
// On the bench's plates (scan_bench --plates, levels 1 and 2) the gaps'
// tunnels are bare at 3-3.5 and holes with scanned walls at 2-2.5; clean
// triple tori at 4,000 points reach 3 (seed 7).  3.5 warns no clean scan,
// and leaves gap tunnels bare only at 3 unwarned.
constexpr float kBareHandleReach = 3.5f;

// Where the encoder built surface itself, as points `spacing` apart: the
// points a joined tube added, and the bridged tubes' triangles sampled.
PointCloud own_tube_points(const Encoding& e, double spacing) {
  PointCloud own;
  own.xyz = e.tubes.at;
  const std::vector<float>& t = e.stages.bridged_tube_triangles;
  for (size_t i = 0; i + 9 <= t.size(); i += 9) {
    const float *a = &t[i], *b = &t[i + 3], *c = &t[i + 6];
    double longest = 0;
    for (const auto& [p, q] : {std::pair{a, b}, std::pair{b, c}, std::pair{c, a}})
      longest = std::max(longest, std::hypot(double{p[0]} - q[0], double{p[1]} - q[1], double{p[2]} - q[2]));
    // (In double before the cast: a NaN or huge ratio is no int.)
    const double k = spacing > 0 ? std::ceil(longest / spacing) : 1.0;
    const int n = k >= 1 ? static_cast<int>(std::min(k, 64.0)) : 1;
    for (int u = 0; u <= n; ++u)
      for (int v = 0; u + v <= n; ++v)
        for (int k = 0; k < 3; ++k)
          own.xyz.push_back(static_cast<float>((double{a[k]} * (n - u - v) + double{b[k]} * u + double{c[k]} * v) / n));
  }
  return own;
}

// Handles of a closed `test` surface that run through bare area only
// (bare_handles.h), the ones the encoder built itself aside (tubes joined
// across a cut, tubes the bridging stage built between facing holes): their
// surface counts as supported where it was built (own_tube_points), so a
// tube of the encoder's that is not bare cannot hide a bare handle
// elsewhere, as subtracting their count did.  Fills c.bare_handles,
// c.bare_handle_reach, c.bare_handle_at.
void check_bare_handles(ScanCheck& c, const Encoding& e, const TriangleMesh& test, const PointIndex& index) {
  const PointCloud own = own_tube_points(e, c.spacing);
  const std::unique_ptr<PointIndex> own_index = own.size() > 0 ? std::make_unique<PointIndex>(own) : nullptr;
  const std::vector<float> ratios = bare_ratios(test, index, own_index.get());
  const std::vector<float> ladder{2.0f, 2.5f, 3.0f, kBareHandleReach, 4.0f, 5.0f, 6.0f, 8.0f, 12.0f};
  const std::vector<uint32_t> bare = bare_handles_at(test, ratios, ladder);
  for (size_t r = 0; r < ladder.size(); ++r)
    if (bare[r] > 0) c.bare_handle_reach = ladder[r];
  if (bare[3] == 0) return;
  std::vector<uint32_t> at;
  c.bare_handles = bare_handles(test, ratios, kBareHandleReach, &at);
  for (uint32_t v : at) c.bare_handle_at.push_back({test.positions[3 * v], test.positions[3 * v + 1], test.positions[3 * v + 2]});
}

std::string fmt(const char* f, double x) {
  char b[96];
  std::snprintf(b, sizeof b, f, x);
  return b;
}

}  // namespace

ScanCheck check_scan(const Encoding& e, const PointIndex& index, unsigned threads) {
  ScanCheck c;
  const PointCloud& pc = index.points();
  if (pc.size() == 0) return c;
  c.spacing = point_spacing(index, 1, 0.5);
  TriangleMesh finest;
  if (!e.levels.positions.empty()) {
    const size_t l = measured_level(e);
    finest.positions = e.levels.positions[l];
    finest.triangles = e.levels.triangles[l];
  } else {
    finest = e.control;
  }
  // (Refinement keeps the topology: components, boundary loops and genus
  // are the same on every level.)
  const MeshInfo info = mesh_info(finest);
  c.surface_components = info.components;
  c.open = !info.closed;
  c.boundary_loops = c.open ? static_cast<uint32_t>(boundary_loops(finest).size()) : 0;
  // Clusters as the outlier pass counts them; tiny ones are not objects.
  // When that pass ran, its count stands (it dropped the small ones, which
  // leaves the others as they were), and a second pass over a large scan
  // is saved.
  if (e.outliers.clustered && e.outliers.kept() == pc.size()) {
    c.point_clusters = static_cast<uint32_t>(e.outliers.clusters - e.outliers.clusters_dropped);
  } else {
    uint32_t count = 0;
    const std::vector<uint32_t> cluster = point_clusters(index, cluster_radius(index), &count);
    std::vector<size_t> size(count, 0);
    for (uint32_t id : cluster) ++size[id];
    for (size_t s : size) c.point_clusters += static_cast<double>(s) >= 0.02 * static_cast<double>(pc.size());
    // No cluster that large: the points are scattered (a coarse mesh's
    // vertices), and their number of pieces is the figure to show.
    if (c.point_clusters == 0) c.point_clusters = count;
  }
  const size_t measured = e.levels.positions.empty() ? 0 : measured_level(e);
  c.clamped_level = static_cast<uint32_t>(clamp_level(e, measured));
  if (const LevelStats* st = level_stats(e, c.clamped_level))
    c.clamped_share = static_cast<double>(st->clamped) / static_cast<double>(std::max<size_t>(1, st->odd));
  // Uncovered area: triangles whose centroid has no point near.
  double total = 0, bare = 0;
  // Uneven scans have sparse stretches a few median spacings wide that are
  // still surface: the reach is at least twice the sparse end's spacing.
  const double reach = std::max(kUncoveredReach * c.spacing, 2 * point_spacing(index, 1, 0.99));
  const double reach2 = reach * reach;
  for (size_t t = 0; t < finest.triangle_count(); ++t) {
    const float* a = &finest.positions[3 * finest.triangles[3 * t]];
    const float* b = &finest.positions[3 * finest.triangles[3 * t + 1]];
    const float* d = &finest.positions[3 * finest.triangles[3 * t + 2]];
    float centre[3];
    for (int k = 0; k < 3; ++k) centre[k] = (a[k] + b[k] + d[k]) / 3.0f;
    const double area = triangle_area(finest, t);
    const uint32_t p = index.nearest(centre);
    double d2 = 0;
    for (int k = 0; k < 3; ++k) d2 += std::pow(centre[k] - double{pc.xyz[3 * p + k]}, 2);
    total += area;
    if (d2 > reach2) bare += area;
  }
  c.uncovered_share = total > 0 ? bare / total : 0;
  c.points_to_surface = sampled_points_to_mesh(pc, finest, threads);
  // A closed surface over points that end at two facing rims (a band the
  // scan missed right round a tube) must join them; capped, a handle is
  // lost.  The carving can cap such ends before the bridging stage sees
  // them as holes (and its doubtful pairs count), so the points are asked
  // directly.  The winding-number test runs on the finest level of at most
  // kJoinTestTriangles triangles: coarse enough to be quick, and a bridge
  // is in every level.
  //
  // The rims are looked for twice: as the join looks (encode.cpp), and
  // looser, with 7 of 12 sectors round the axis instead of 8.  A sparse
  // scan's rim has wider gaps: on the hole sweep (scan_bench --hole-sweep)
  // a triple torus cut right round a tube at 8,000 points came out with a
  // handle too few and no warning, one end's rim covering 7 sectors.  The
  // looser rims are only warned about, never joined: at 4,000 points they
  // also pair two rims round bands the surface did bridge (two right rows
  // warned), which a join would rebuild the control mesh for in vain.
  // Those two were arcs of a band's side: a pair that needs a loose rim
  // must also have both rims facing each other and tube radii within 0.75
  // of each other (rims_face_as_one_tube), and neither is warned now.
  //
  // And a third time, split finer (split_rim_options): where the missed
  // band runs a long way round a ring, its two ends are oblique and the
  // boundary points between them link both into one group that reads as
  // one hole in a wall, and no pair is found (four silent rows of the
  // 4,000-point hole sweep).  Linked over 1.5 neighbourhood radii instead
  // of 2, the ends come apart, with fewer sectors; so do arcs of plain
  // holes' edges, so a split pair counts only where the middle of its gap
  // is at least a tube's radius from the surface (gap_clearance).
  //
  // And a fourth time, from the split rims that still run most of the way
  // round (full_rim_options): a tube's end cut obliquely reads a higher
  // wall (its points' normals tilt toward the cut's plane), over
  // tube_end_pairs' bound (the 4,000-point double torus cut 15% from
  // (0.2,-1,-0.4): 0.57).  Such a pair counts with walls up to 0.65 when
  // both ends face each other with tube radii within 0.9 of each other
  // (one tube's two ends; arcs of one hole's edge read 0.6-0.7) and the
  // gap is a tube's radius clear.
  if (!c.open && info.components > 0) {
    RimOptions loose;
    loose.min_sectors = 7;
    // The boundary points once; each option set only links them.
    const RimPoints rim_points = find_rim_points(index, size_t{1} << 16);
    const std::vector<PointRim> loose_rims = link_rims(rim_points, loose);
    std::vector<PointRim> rims;
    for (const PointRim& r : loose_rims)
      if (r.sectors >= RimOptions{}.min_sectors) rims.push_back(r);
    const std::vector<std::pair<size_t, size_t>> pairs = tube_end_pairs(rims), loose_pairs = tube_end_pairs(loose_rims);
    const std::vector<PointRim> split_rims = link_rims(rim_points, split_rim_options());
    const std::vector<std::pair<size_t, size_t>> split_pairs = tube_end_pairs(split_rims);
    const std::vector<PointRim> full_rims = link_rims(rim_points, full_rim_options());
    std::vector<std::pair<size_t, size_t>> full_pairs;
    for (const auto& [a, b] : tube_end_pairs(full_rims, kFullRimMaxWall))
      if (rims_face_as_one_tube(full_rims[a], full_rims[b], kFullRimSameTube)) full_pairs.emplace_back(a, b);
    if (!pairs.empty() || !loose_pairs.empty() || !split_pairs.empty() || !full_pairs.empty()) {
      TriangleMesh test = e.control;
      for (size_t l = 0; l < e.levels.triangles.size(); ++l)
        if (e.levels.triangles[l].size() / 3 <= kJoinTestTriangles)
          test = TriangleMesh{e.levels.positions[l], e.levels.triangles[l]};
      for (const auto& [a, b] : pairs) c.capped_rim_pairs += !surface_joins(test, rims[a], rims[b]);
      uint32_t loose_capped = 0;
      for (const auto& [a, b] : loose_pairs) {
        const PointRim &ra = loose_rims[a], &rb = loose_rims[b];
        // A pair the strict rims also make keeps tube_end_pairs' rule; one
        // that needs a looser rim must face as one tube's two ends.
        const bool strict = ra.sectors >= RimOptions{}.min_sectors && rb.sectors >= RimOptions{}.min_sectors;
        if (!strict && !rims_face_as_one_tube(ra, rb)) continue;
        loose_capped += !surface_joins(test, ra, rb);
      }
      c.capped_rim_pairs = std::max(c.capped_rim_pairs, loose_capped);
      // The split rims count only where the gap between them is empty
      // space (kMinGapClearance): they pair arcs of one hole's edge too.
      uint32_t split_capped = 0, full_capped = 0;
      if (!split_pairs.empty() || !full_pairs.empty()) {
        const TriangleTree tree(test);
        const auto capped_clear = [&](const PointRim& ra, const PointRim& rb) {
          return !surface_joins(test, ra, rb) && gap_clearance(tree, ra, rb) >= kMinGapClearance;
        };
        for (const auto& [a, b] : split_pairs) split_capped += capped_clear(split_rims[a], split_rims[b]);
        for (const auto& [a, b] : full_pairs) full_capped += capped_clear(full_rims[a], full_rims[b]);
      }
      c.capped_rim_pairs = std::max({c.capped_rim_pairs, split_capped, full_capped});
    }
  }

  if (!c.open && info.components > 0) {
    TriangleMesh test = e.control;
    for (size_t l = 0; l < e.levels.triangles.size(); ++l)
      if (e.levels.triangles[l].size() / 3 <= kJoinTestTriangles) test = TriangleMesh{e.levels.positions[l], e.levels.triangles[l]};
    // Cut 1-to-4 at edge midpoints up to a quarter of that size: the
    // tunnel through a thin part's gap is a wall a few triangles tall at
    // coarse levels, and a bare ring needs vertices along its middle.
    while (test.triangle_count() * 4 <= kJoinTestTriangles / 4) test = split_at_midpoints(test);
    check_bare_handles(c, e, test, index);
  }

  if (!c.open && info.components == 1 && e.stages.coarser_genus > info.genus)
    c.lost_handles = static_cast<uint32_t>(e.stages.coarser_genus - info.genus);

  const auto warn = [&](const char* code, const std::string& message) { c.warnings.push_back({code, message}); };
  if (c.surface_components != c.point_clusters)
    warn("components", "the surface has " + std::to_string(c.surface_components) + " component(s) where the points form " +
                           std::to_string(c.point_clusters) +
                           " cluster(s): parts merged or broken up (stray points, or a carving grid too fine or too coarse "
                           "for the sampling; try --grid)");
  if (c.clamped_share > kMaxClamped)
    warn("clamped", fmt("%.1f%%", 100 * c.clamped_share) + " of level " + std::to_string(c.clamped_level) +
                        " displacements clamped (bound " + fmt("%.0f%%", 100 * kMaxClamped) +
                        "): the surface is far from the points in places: a hole the carving leaked through or a sheet "
                        "closed over (try --surface open or --surface closed), or sharp creases the subdivision "
                        "overshoots");
  // A bridged hole is reported, not warned about; with the band between
  // its rim and the last points it leaves about 1.4 times its area bare.
  const double bridged = e.stages.bridged_area + e.tubes.area_share;
  if (c.uncovered_share > kMaxUncovered + 1.5 * bridged)
    warn("uncovered", fmt("%.1f%%", 100 * c.uncovered_share) + " of the surface has no point within " +
                          (c.spacing > 0 ? fmt("%.1f", reach / c.spacing) + " point spacings" : fmt("%.3g", reach) + " model units") + " (bound " + fmt("%.0f%%", 100 * kMaxUncovered) +
                          (bridged > 0 ? fmt(" plus 1.5 times the %.1f%% bridged over holes", 100 * bridged) : "") +
                          "): surface invented where nothing was scanned (holes, an open patch closed over, or stray points)");
  // The bridging stage's doubtful pairs and the points' capped rims are
  // mostly the same openings seen twice: the larger count stands.
  if (const size_t capped = std::max<size_t>(e.stages.doubtful_caps, c.capped_rim_pairs); capped > 0)
    warn("topology", std::to_string(capped) +
                         " pair(s) of openings in the scan were capped that lie close together and face each other: "
                         "each pair may be the two ends of a handle or limb where the scan missed a band, and capping "
                         "them cuts it (the genus may be too low by as much; a scan of the gap, or --surface open "
                         "to keep the ends as boundaries)");
  if (c.bare_handles > 0) {
    std::string where;
    for (const auto& p : c.bare_handle_at) {
      char b[96];
      std::snprintf(b, sizeof b, "%s(%.3g, %.3g, %.3g)", where.empty() ? " near " : ", ", p[0], p[1], p[2]);
      where += b;
    }
    warn("bare_handle", std::to_string(c.bare_handles) + " handle(s) of the surface run only through area with no point within " +
                            fmt("%.0f", kBareHandleReach) + " local point spacings" + where +
                            ": the points do not show these handles (a gap the scan left through a thin part, closed "
                            "over as a hole, where a real hole's wall would be scanned; or a hole filled round a "
                            "tube's far side); the genus may be too high by as much (scan the gap)");
  }
  if (c.lost_handles > 0)
    warn("lost_handle", std::to_string(c.lost_handles) + " handle(s) that the carving showed at coarser grids (genus " +
                            std::to_string(e.stages.coarser_genus) + ", at three grids in a row) are closed in the surface (genus " +
                            std::to_string(info.genus) +
                            "): a tube whose two ends were capped where the scan missed a band round it; the genus may be "
                            "too low by as much (a scan of the band, or --grid with a coarser grid to keep the handle)");
  if (c.spacing > 0 && c.points_to_surface > kMaxDistance * c.spacing)
    warn("distance", "the points lie " + fmt("%.1f", c.points_to_surface / c.spacing) +
                         " point spacings from the surface on average (bound " + fmt("%.0f", kMaxDistance) +
                         "): parts of the scan are not represented (noise, thin parts, or a surface that missed them)");
  if (e.outliers.points_in > 0) {
    // Of the distinct points: merged duplicates lose nothing.
    const double distinct = static_cast<double>(e.outliers.points_in - e.outliers.duplicates);
    const double dropped = static_cast<double>(e.outliers.isolated + e.outliers.cluster_points) / std::max(1.0, distinct);
    if (dropped > kMaxDropped)
      warn("outliers", fmt("%.1f%%", 100 * dropped) + " of the points were dropped as outliers (bound " +
                           fmt("%.0f%%", 100 * kMaxDropped) +
                           "): a very noisy scan, or objects too small to keep (--keep-outliers keeps every point)");
  }
  return c;
}

}  // namespace dbss

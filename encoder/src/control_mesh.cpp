#include "dbss/encoder/control_mesh.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <numbers>
#include <optional>
#include <string>

#include "dbss/encoder/mesh_folds.h"
#include "dbss/encoder/self_intersections.h"
#include "dbss/encoder/open_surface.h"
#include "dbss/encoder/triangle_tree.h"
#include "dbss/encoder/point_index.h"
#include "dbss/encoder/projection.h"
#include "dbss/encoder/shell_mesh.h"

namespace dbss {

namespace {
// Empty (inside) cells per occupied cell under which a carving may be a
// slab around a sheet rather than a solid, so the one-sided cut is tried
// (and kept only if it removes one of two sides): a sphere of 50 cells
// across has about 4, a triple torus's tubes 0.7, a sheet none.  A torus
// whose carving leaked through a hole into part of its tube had 0.3.
constexpr double kMaybeLeaked = 1.0;
// Share of the shell behind the points (SheetCut::behind) that counts as a
// second side.
constexpr double kLeakCut = 0.01;
// Share of the points farther than two median spacings from a one-sided
// sheet above which the sheet does not explain them (see build_sheet).
constexpr double kSheetMiss = 0.12;
// Share of the area bridged above which a leak at a finer grid than the
// search's closed one is not worth it (the bunny's base: 0.3%).
constexpr double kMaxLeakBridged = 0.02;
// Boundary loops shorter than this many cells are closed even in open mode.
constexpr double kPinhole = 8;
// Under `auto`, holes are bridged when the patches would cover less than
// this share of the closed surface: a scan missing the side it stood on
// needs around a tenth, a half sphere a third.
constexpr double kMaxBridged = 0.2;

// A stage's start on the wall clock and in CPU time of the process (every
// thread summed: the grid search carves two grids at once).
struct Stamp {
  std::chrono::steady_clock::time_point wall;
  double cpu;
};
double process_cpu() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}
struct Clock {
  static Stamp now() { return {std::chrono::steady_clock::now(), process_cpu()}; }
};
double since(const Stamp& t) { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t.wall).count(); }
double cpu_since(const Stamp& t) { return process_cpu() - t.cpu; }

Status check_stage(const TriangleMesh& m, const MeshInfo& want, const char* stage) {
  const MeshInfo got = mesh_info(m);
  // The Euler characteristic with the components and closedness pins the
  // genus of a closed surface, and genus plus boundary loops of an open one.
  if (!got.manifold || got.closed != want.closed || got.components != want.components || got.euler != want.euler)
    return Status(ErrorCode::internal, std::string(stage) + " changed the topology: " + std::to_string(got.components) +
                                           " components, Euler characteristic " + std::to_string(got.euler) + " (manifold " +
                                           std::to_string(got.manifold) + ", closed " + std::to_string(got.closed) +
                                           "), expected " + std::to_string(want.components) + " with " +
                                           std::to_string(want.euler) + (want.closed ? ", closed" : ", open"));
  return {};
}

// Empty cells the carving did not reach (and cells filled to enclose them).
size_t inside_cells(const CellGrid& g) {
  return static_cast<size_t>(std::count_if(g.state.begin(), g.state.end(), [](uint8_t x) {
    return x == CellGrid::kInside || x == CellGrid::kFilled;
  }));
}

std::string fmt(const char* f, double x) {
  char b[64];
  std::snprintf(b, sizeof b, f, x);
  return b;
}

// The open-sheet path: one side of the carved slab, shrink-wrapped, trimmed
// to the points, holes optionally closed.  Leaves the result in s.wrapped;
// returns false (s untouched but for s.surface_reason) when the sheet does
// not explain the points and the closed path should run instead.
bool build_sheet(ControlMeshStages& s, const PointIndex& index, const ControlMeshOptions& o, double inside_share,
                 int leaking_grid) {
  const double spacing = point_spacing(index, 1, 0.5);
  const auto normals = oriented_normals(index);
  struct Carved {
    CellGrid cells;
    CarvingStats carving;
    TriangleMesh shell;
    MeshInfo info;
  };
  std::optional<Carved> coarse;  // the search's carving, while a finer one is tried
  const auto fall_back = [&](std::string why) {
    s.surface_reason = std::move(why);
    if (coarse) {
      s.cells = std::move(coarse->cells);
      s.carving = coarse->carving;
      s.shell = std::move(coarse->shell);
      s.shell_info = coarse->info;
    }
    return false;
  };
  const auto behind_share = [&](const SheetCut& c) {
    return static_cast<double>(c.behind) / static_cast<double>(std::max<size_t>(1, s.shell.triangle_count()));
  };
  const auto usable = [](const SheetCut& c) { return c.sheet.triangle_count() > 0 && mesh_info(c.sheet).manifold; };
  const std::vector<uint8_t> thin = thin_under(s.shell, s.cells);
  SheetCut cut = cut_to_sheet(s.shell, index, normals, &thin);
  // A carving that did not leak (a thin closed shape: a torus's tube, a
  // plate) has one side only: next to none of its shell lies behind the
  // points over thin solid.  A leak into part of a double torus's tube put
  // 2% of the shell there; a noisy sphere's flipped normals 0.04%, a triple
  // torus sampled ten times denser on one side 0.6%.
  const std::string one_side = "closed: the carving encloses " + fmt("%.2g", inside_share) +
                               " empty cells per occupied one, and its shell faces the points from one side only";
  // Whether the search's own carving is closed (one-sided), should a finer
  // one open more gaps than are worth bridging.
  const bool coarse_closed = usable(cut) && behind_share(cut) < kLeakCut;
  if (leaking_grid == 0 && !usable(cut)) return fall_back("closed: cutting the carved slab to one side failed");
  if (leaking_grid == 0 && o.surface != SurfaceMode::open && behind_share(cut) < kLeakCut) return fall_back(one_side);
  // The automatic grid search stops short of the grids that leak, and a
  // sheet leaks at every grid: the sheet is cut from the finest grid the
  // sampling supports (cells of one spacing at its sparse end; the carving
  // still closes gaps of two), the search's carving kept should it fail.
  const int want = std::clamp(static_cast<int>(s.carving.grid * s.cells.cell / point_spacing(index, 1, 0.99)), 8, 256);
  // (A grid a step or two finer gains too little to be worth the cut.)
  if (o.grid == 0 && want > s.carving.grid + s.carving.grid / 8) {
    CarvingStats stats;
    CellGrid cells = carve(index.points(), want, &stats);
    auto shell = triangulate_shell(cells);
    if (shell.ok()) {
      const std::vector<uint8_t> fine_thin = thin_under(shell.value(), cells);
      SheetCut fine = cut_to_sheet(shell.value(), index, normals, &fine_thin);
      if (usable(fine)) {
        coarse = Carved{std::move(s.cells), s.carving, std::move(s.shell), s.shell_info};
        s.cells = std::move(cells);
        s.carving = stats;
        s.shell = std::move(shell).value();
        s.shell_info = mesh_info(s.shell);
        cut = std::move(fine);
      }
    }
  }
  if (!usable(cut)) return fall_back("closed: cutting the carved slab to one side failed");
  if (o.surface != SurfaceMode::open && behind_share(cut) < kLeakCut)
    return fall_back(leaking_grid ? "closed: grids of " + std::to_string(leaking_grid) +
                                        " cells and finer leak, but not into a second side"
                                  : one_side);
  const double cell = s.cells.cell;
  TriangleMesh sheet = std::move(cut.sheet);
  ShrinkWrapStats wrap = shrink_wrap(sheet, index, o.shrink_wrap);
  // The slab's rim overhangs the last points by up to a cell or two.
  const size_t trimmed = trim_unsupported(sheet, index, std::max(2 * spacing, 0.75 * cell));
  if (sheet.triangle_count() == 0) return fall_back("closed: no part of the one-sided sheet lies on the points");
  // Does one side explain the points?  A thin closed part (a plate, a
  // blade thinner than two cells) carves like a sheet too, but then a large
  // share of its points (those of the other side) lie a thickness away.
  // Points farther than two spacings from the sheet: thin parts 16-43%
  // (oni, a rotor, a blade, a plate); one-sided scans 0-0.2%, a noisy
  // lidar scan with walls and roofs 8%.
  size_t far_points = 0;
  {
    const TriangleTree tree(sheet);
    const std::vector<float>& xyz = index.points().xyz;
    for (size_t i = 0; i < xyz.size() / 3; ++i) {
      const double p[3] = {xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]};
      far_points += tree.distance(p) > 2 * spacing;
    }
  }
  const double far_share = static_cast<double>(far_points) / static_cast<double>(std::max<size_t>(1, index.points().size()));
  if (o.surface == SurfaceMode::automatic && far_share > kSheetMiss)
    return fall_back("closed: the carving encloses almost no volume, but " + fmt("%.0f", 100 * far_share) +
                     "% of the points lie over two spacings from one side of it (two sides close together)");
  // Pinholes (a loop a few cells round) are gaps in the sampling or notches
  // the cut left, not where the scan ends: closed in every mode.
  // So are loops no wider than the gaps of the sparsest sampling: a hole
  // the points themselves leave (a saddle sampled thinly), not their end.
  // At most twice the pinholes' length: strays kept (--keep-outliers) or a
  // sparse tail of the sampling must not close where a scan really ends.
  const double gap = 4 * std::numbers::pi * point_spacing(index, 1, 0.99);  // perimeter of a circle two gaps wide
  const HoleFill pinholes = fill_holes(sheet, cell, std::max(kPinhole * cell, std::min(gap, 2 * kPinhole * cell)));
  const double sheet_area = mesh_area(sheet);
  TriangleMesh filled = sheet;
  const HoleFill fill = fill_holes(filled, cell, 1e300, /*bridge=*/true);
  const double hole_share = fill.area / std::max(1e-300, fill.area + sheet_area);
  // A closed carving was at hand (the search's): a leak at a finer grid is
  // worth bridging only where it is a hole or two (the bunny's base, 0.3%
  // of the area), not a sampling too sparse for that grid all over (a
  // triple torus at one spacing per cell: 30 gaps, 8.5%).
  if (leaking_grid && coarse_closed && o.surface != SurfaceMode::open && hole_share > kMaxLeakBridged)
    return fall_back("closed: grids of " + std::to_string(leaking_grid) + " cells and finer leak through " +
                     std::to_string(fill.loops) + " gaps in the points (" + fmt("%.1f", 100 * hole_share) +
                     "% of the area)");
  bool close = o.surface == SurfaceMode::closed;
  const std::string tubes = fill.bridges ? " (" + std::to_string(2 * fill.bridges) + " of them the ends of " +
                                               std::to_string(fill.bridges) + " tube(s) the scan cut, joined)"
                                         : "";
  const std::string why_thin = leaking_grid ? "grids of " + std::to_string(leaking_grid) +
                                                 " cells and finer leak through gaps in the points"
                                           : "the carving encloses " + fmt("%.2g", inside_share) +
                                                 " empty cells per occupied one (it leaks through gaps in the points)";
  if (o.surface == SurfaceMode::automatic) {
    // A few holes in an object's scan (the side it stood on) are closed; a
    // patch whose boundary would need more than this to close stays open.
    close = fill.loops > 0 && hole_share < kMaxBridged;
    s.surface_reason = close ? "closed: " + why_thin + "; its " + std::to_string(fill.loops) + " hole(s), " +
                                   fmt("%.1f", 100 * hole_share) + "% of the area, are bridged" + tubes
                             : "open: " + why_thin + "; closing it would take " + fmt("%.0f", 100 * hole_share) +
                                   "% of the area from no points";
  } else if (close) {
    s.surface_reason = "closed (asked): " + why_thin + "; " + std::to_string(fill.loops) + " hole(s), " +
                       fmt("%.1f", 100 * hole_share) + "% of the area, bridged" + tubes;
  } else {
    s.surface_reason = "open (asked)";
  }
  // Trimming can leave two patches touching at one vertex (a bow tie),
  // which no later stage can carry: the closed shell it came from is kept.
  if (!mesh_info(close ? filled : sheet).manifold)
    return fall_back("closed: the one-sided sheet is not a manifold once trimmed to the points");
  s.open = !close;
  s.cut_triangles = cut.removed + trimmed;
  s.pinholes = pinholes.loops;
  s.bridged_area = close ? hole_share : 0;
  s.doubtful_caps = close ? fill.doubtful_pairs : 0;
  s.bridged_tubes = close ? fill.bridges : 0;
  if (close) s.bridged_tube_triangles = fill.bridge_triangles;
  s.wrap_stats = wrap;
  s.wrapped = close ? std::move(filled) : std::move(sheet);
  return true;
}
}  // namespace

const char* surface_mode_name(SurfaceMode m) {
  switch (m) {
    case SurfaceMode::closed: return "closed";
    case SurfaceMode::open: return "open";
    default: return "auto";
  }
}

Result<ControlMeshStages> build_control_mesh(const PointCloud& points, const ControlMeshOptions& o) {
  return build_control_mesh(PointIndex(points), o);
}

Result<ControlMeshStages> build_control_mesh(const PointIndex& index, const ControlMeshOptions& o) {
  const PointCloud& points = index.points();
  ControlMeshStages s;
  int leaking_grid = 0;  // the automatic search stopped at grids this fine that leak (0: none did)
  int64_t coarser_handles = 0;  // handles coarser grids of the search showed that the chosen one closed
  auto stage = [&](const char* name) {
    if (o.on_stage) o.on_stage(name);
  };
  stage("choosing the grid");
  auto t = Clock::now();
  if (o.grid > 0) {
    s.seconds.grid = since(t), s.cpu_seconds.grid = cpu_since(t);
    stage("carving cells");
    t = Clock::now();
    s.cells = carve(points, o.grid, &s.carving, o.grid_shift);
  } else {
    // The search carves its choice on the way: its time is the grid's.
    CarvingChoice chosen = choose_carving(points, index);
    s.cells = std::move(chosen.cells);
    s.carving = chosen.stats;
    leaking_grid = chosen.leaking_grid;
    coarser_handles = chosen.euler - chosen.coarser_euler;
    s.seconds.grid = since(t), s.cpu_seconds.grid = cpu_since(t);
    t = Clock::now();
  }
  s.seconds.carve = since(t), s.cpu_seconds.carve = cpu_since(t);

  stage("triangulating");
  t = Clock::now();
  auto shell = triangulate_shell(s.cells, true, &s.shell_info);
  if (!shell.ok()) return shell.status();
  s.shell = std::move(shell).value();
  if (coarser_handles > 0 && s.shell_info.components == 1) s.coarser_genus = s.shell_info.genus + coarser_handles;
  s.seconds.triangulate = since(t), s.cpu_seconds.triangulate = cpu_since(t);

  // Open or closed: a carving that encloses next to no volume is a slab
  // around a sheet of points (an open scan, or a closed one whose carving
  // leaked through a hole).
  const double inside_share =
      static_cast<double>(inside_cells(s.cells)) / static_cast<double>(std::max<size_t>(1, s.carving.occupied));
  bool sheet = false;
  if (o.surface == SurfaceMode::open || inside_share < kMaybeLeaked || leaking_grid) {
    stage("cutting the open sheet");
    t = Clock::now();
    sheet = build_sheet(s, index, o, inside_share, leaking_grid);
    s.seconds.shrink_wrap = since(t), s.cpu_seconds.shrink_wrap = cpu_since(t);
    if (o.surface == SurfaceMode::open && !sheet)
      return Status(ErrorCode::invalid_argument, "--surface open: " + s.surface_reason.substr(s.surface_reason.find(':') + 2));
  } else {
    s.surface_reason = std::string(o.surface == SurfaceMode::closed ? "closed (asked)" : "closed") +
                       ": the carving encloses " + fmt("%.2g", inside_share) + " empty cells per occupied one";
  }
  if (!sheet) {
    stage("shrink-wrapping");
    t = Clock::now();
    s.wrapped = s.shell;
    s.wrap_stats = shrink_wrap(s.wrapped, index, o.shrink_wrap);
    // (+=: a sheet tried and given up on above counts in this stage too.)
    s.seconds.shrink_wrap += since(t), s.cpu_seconds.shrink_wrap += cpu_since(t);
    // Shrink-wrapping moves vertices only, and the topology is the
    // triangles': equal triangles are the shell's topology, checked without
    // describing the whole mesh again.
    if (s.wrapped.triangles != s.shell.triangles) return Status(ErrorCode::internal, "shrink-wrapping changed the triangles");
  }
  const MeshInfo wrapped_info = sheet ? mesh_info(s.wrapped) : s.shell_info;

  stage("simplifying");
  t = Clock::now();
  // An open sheet, or one with a sizeable bridged patch, gets the faces of a
  // shell twice its size: its rim and its patches need them.  With one share
  // hippo1.ply clamped 3.0% of its displacements (1.3% with two), and
  // spheres and tori with a bridged 10% hole came out 1.7-2.2 times farther
  // from their points.  A closed sheet with a pinhole or two bridged (the
  // bunny's base, 0.3% of its area) counts like any closed shell: twice
  // the faces there doubled its control mesh for no gain in its level 2
  // against level 3.
  const bool rim_or_patch = sheet && (s.open || s.bridged_area >= kMaxLeakBridged);
  const uint32_t target = o.control_faces ? o.control_faces
                                          : default_control_faces(static_cast<uint32_t>(rim_or_patch ? 2 * s.wrapped.triangle_count()
                                                                                                      : sheet ? s.wrapped.triangle_count()
                                                                                                      : s.shell.triangle_count()),
                                                                  wrapped_info.genus);
  s.target_faces = target;
  auto simplified = simplify_mesh(s.wrapped, target, &s.simplify_stats);
  if (!simplified.ok()) return simplified.status();
  s.simplified = std::move(simplified).value();
  s.seconds.simplify = since(t), s.cpu_seconds.simplify = cpu_since(t);
  if (Status st = check_stage(s.simplified, wrapped_info, "simplification"); !st.ok()) return st;

  stage("shaping");
  t = Clock::now();
  // Flips and relaxation toward a mesh the butterfly's stencils like (no
  // slivers, valences near 6); projection below then puts the vertices on
  // the points.
  s.control = s.simplified;
  s.shape_stats = improve_shape(s.control, &index, o.shape);
  s.seconds.shape = since(t), s.cpu_seconds.shape = cpu_since(t);
  if (Status st = check_stage(s.control, wrapped_info, "shaping"); !st.ok()) return st;

  stage("projecting");
  t = Clock::now();
  // Smooth out any fold the collapses left, then project: the projection
  // refuses moves that fold, so the control mesh ends fold-free.  (Coarse:
  // the folded edges' vertices only, and no round that folds more; see
  // mesh_folds.h.)
  s.untangled = untangle_folds(s.control, 8, /*coarse=*/true);
  // Collapses can make distant sheets cross; projection below keeps the
  // mesh free of crossings only if it starts free of them.
  s.relaxed = relax_self_intersections(s.control);
  const std::vector<float> before = s.control.positions;
  // A vertex whose move was refused may go once its neighbours have moved.
  s.projection_skipped = project_to_points(s.control, index);
  for (int again = 0; again < 3 && s.projection_skipped > 0; ++again) s.projection_skipped = project_to_points(s.control, index);
  if (s.bridged_area > 0) {
    // A bridged hole has no points to project onto: vertices more than two
    // cells from any point stay on the patch (their nearest point is on the
    // hole's rim).  Nearer ones go to the rim like the rest: at half a cell
    // the double torus's bridged tube clamped 4% of its displacements, at
    // two cells 2.8%.
    const double reach = 2.0 * s.cells.cell;
    for (size_t v = 0; v < s.control.vertex_count(); ++v) {
      const float* p = &before[3 * v];
      const uint32_t c = index.nearest(p);
      double d2 = 0;
      for (int a = 0; a < 3; ++a) d2 += std::pow(p[a] - double{points.xyz[3 * c + a]}, 2);
      if (d2 > reach * reach)
        for (int a = 0; a < 3; ++a) s.control.positions[3 * v + a] = p[a];
    }
  }
  // Projection checks folds only locally; on thin parts a vertex can still
  // pass through the opposite side.
  s.projection_skipped += undo_self_intersections(s.control, before);
  s.seconds.project = since(t), s.cpu_seconds.project = cpu_since(t);
  if (o.shape.enabled) {
    // Jumps onto the points move vertices by up to a point spacing
    // sideways, a lot next to a short edge (a sphere's slivers went from
    // 0.2% to 1.2% of its triangles): flips, and moves from point to point,
    // mend them with the vertices left on the points.
    t = Clock::now();
    ShapeOptions on_points = o.shape;
    on_points.snap = true;
    const ShapeStats again = improve_shape(s.control, &index, on_points);
    s.shape_stats.flips += again.flips;
    s.shape_stats.moves += again.moves;
    s.shape_stats.rounds_undone += again.rounds_undone;
    s.shape_stats.after = again.after;
    s.seconds.shape += since(t), s.cpu_seconds.shape += cpu_since(t);
    if (Status st = check_stage(s.control, wrapped_info, "shaping"); !st.ok()) return st;
  }
  return s;
}

}  // namespace dbss

// rim_probe: the self-check's point rims and their candidate pairs on the
// hole sweep's rows (scan_bench --hole-sweep --surface closed --levels 1)
// and the clean tori, with the gap's clearance along the path a join would
// follow.  A measurement probe for issue 13 (bench/scan_bench.md,
// sixteenth session).  Lines: ROW (the surface's genus and the self-check's
// warnings), FULL (the pairs check_scan's fourth look weighs), RIM (rims
// linked over 1.25 and 1.5 radii, down to 3 sectors and 5 points), OPEN
// (the mean of each rim's points' empty-sector directions, toward the
// other end) and PAIR (every pair under 6 radii apart: size, mean wall,
// axes' facing, tube radii's ratio, sectors, joined, chord clearance, and
// the Hermite path's largest clearance outside the surface, least over its
// middle half, samples inside).
// usage: rim_probe [--points N] [--clean] [NAME_PART...]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "../tests/defect_shapes.h"
#include "dbss/encoder/encode.h"
#include "dbss/encoder/mesh_info.h"
#include "dbss/encoder/point_distances.h"
#include "dbss/encoder/point_rims.h"
#include "dbss/encoder/triangle_tree.h"

namespace {

namespace dt = dbss::test;
using V3 = std::array<double, 3>;

V3 sub(V3 a, V3 b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(V3 a, V3 b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
double len(V3 a) { return std::sqrt(dot(a, a)); }

// Hermite curve from a.centre leaving against ta to b.centre arriving along tb.
V3 hermite(const dbss::PointRim& a, const dbss::PointRim& b, V3 ta, V3 tb, double t) {
  const double gap = len(sub(b.centre, a.centre));
  const double h00 = 2 * t * t * t - 3 * t * t + 1, h10 = t * t * t - 2 * t * t + t, h01 = -2 * t * t * t + 3 * t * t,
               h11 = t * t * t - t * t;
  V3 p;
  for (int c = 0; c < 3; ++c) p[c] = h00 * a.centre[c] + h10 * (-ta[c]) * gap + h01 * b.centre[c] + h11 * tb[c] * gap;
  return p;
}

struct Profile {
  double max_out = 0;  // largest clearance of an outside sample
  double mid_band = 1e9;  // least clearance over the middle half (t in [0.25, 0.75])
  int inside = 0;
};

Profile profile(const dbss::TriangleMesh& test, const dbss::TriangleTree& tree, const dbss::PointRim& a,
                const dbss::PointRim& b, V3 ta, V3 tb) {
  const double tube = std::max(a.tube_radius, b.tube_radius);
  Profile p;
  for (int i = 1; i < 16; ++i) {
    const double t = i / 16.0;
    const V3 q = hermite(a, b, ta, tb, t);
    const double d = tree.distance(q.data()) / tube;
    const bool in = dbss::inside_mesh(test, q);
    p.inside += in;
    if (!in) p.max_out = std::max(p.max_out, d);
    if (t >= 0.25 && t <= 0.75) p.mid_band = std::min(p.mid_band, in ? 0.0 : d);
  }
  return p;
}

// The mean of a rim's boundary points' empty-sector directions
// (RimPoints::into): its points found again by linking as link_rims does
// (boundary points within `link` times their reach) and picking the group
// whose centroid is the rim's centre.
V3 opening_of(const dbss::RimPoints& rp, double link, const dbss::PointRim& rim) {
  const size_t m = rp.edge.size();
  std::vector<uint32_t> parent(m);
  for (uint32_t i = 0; i < m; ++i) parent[i] = i;
  const auto find = [&](uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  const dbss::PointIndex index(rp.edge);
  std::vector<uint32_t> near;
  for (size_t i = 0; i < m; ++i) {
    index.within(&rp.edge.xyz[3 * i], static_cast<float>(link * rp.reach[i]), near);
    for (uint32_t j : near) parent[find(static_cast<uint32_t>(i))] = find(j);
  }
  std::vector<std::vector<uint32_t>> groups(m);
  for (uint32_t i = 0; i < m; ++i) groups[find(i)].push_back(i);
  for (const auto& g : groups) {
    if (g.empty()) continue;
    V3 c{0, 0, 0}, o{0, 0, 0};
    for (uint32_t i : g)
      for (int k = 0; k < 3; ++k) c[k] += rp.edge.xyz[3 * i + k] / static_cast<double>(g.size()), o[k] += rp.into[i][k] / static_cast<double>(g.size());
    if (len(sub(c, rim.centre)) < 1e-4) return o;
  }
  return {0, 0, 0};
}

}  // namespace

int main(int argc, char** argv) {
  size_t points = 4000;
  bool clean = false;
  std::vector<std::string> only;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--points" && i + 1 < argc) points = std::stoul(argv[++i]);
    else if (a == "--clean") clean = true;
    else only.push_back(a);
  }
  struct Row {
    std::string name;
    dbss::PointCloud pc;
    long long genus;
  };
  const auto shapes = dt::genus_shapes();
  const dt::Vec3 directions[] = {{0.3, 0.2, 1.0}, {1, 0, 0}, {0, 1, 0.3}, {-1, 0.5, 0.2}, {0.2, -1, -0.4}, {0, 0, -1}};
  for (const char* name : {"torus", "double torus", "triple torus"}) {
    const dt::Shape* s = dt::find_shape(shapes, name);
    std::vector<std::pair<std::string, std::function<dbss::PointCloud()>>> rows;
    if (clean) {
      for (uint32_t seed : {5u, 7u, 11u, 13u, 17u, 19u, 23u, 29u})
        rows.emplace_back(std::string(name) + " seed " + std::to_string(seed),
                          [s, points, seed] { return dt::sample_sdf(s->sdf, s->lo, s->hi, points, seed); });
    } else {
      for (const dt::Vec3& d : directions)
        for (double share : {0.10, 0.15}) {
          char label[96];
          std::snprintf(label, sizeof label, "%s %.0f%% (%g,%g,%g)", name, 100 * share, d[0], d[1], d[2]);
          rows.emplace_back(label, [s, points, d, share] {
            return dt::with_hole(dt::sample_sdf(s->sdf, s->lo, s->hi, points, 5), d, share);
          });
        }
    }
    for (auto& row : rows) {
      // (Named, not a structured binding: clang 14 refuses a binding
      // captured by a lambda.)
      const std::string& label = row.first;
      const auto& make = row.second;
      if (!only.empty() && std::none_of(only.begin(), only.end(), [&](const std::string& o) { return label.find(o) != std::string::npos; }))
        continue;
      dbss::EncodeOptions o;
      o.levels = 1;
      o.control.surface = dbss::SurfaceMode::closed;
      auto r = dbss::encode_points(make(), o);
      if (!r.ok()) continue;
      const dbss::Encoding& e = r.value();
      const dbss::TriangleMesh finest{e.levels.positions.back(), e.levels.triangles.back()};
      const dbss::MeshInfo info = dbss::mesh_info(finest);
      dbss::TriangleMesh test = e.control;
      for (size_t l = 0; l < e.levels.triangles.size(); ++l)
        if (e.levels.triangles[l].size() / 3 <= (size_t{1} << 16)) test = dbss::TriangleMesh{e.levels.positions[l], e.levels.triangles[l]};
      const dbss::TriangleTree tree(test);
      const dbss::PointIndex index(e.points);
      const dbss::RimPoints rp = dbss::find_rim_points(index);
      std::string warn;
      for (const auto& w : e.check.warnings) warn += (warn.empty() ? "" : ",") + w.code;
      const bool lost = info.closed && info.components == 1 && info.genus < s->genus;
      std::printf("ROW %s | %s g%lld/%lld comp%u open%d warn=%s capped=%u\n", label.c_str(), lost ? "LOST" : "ok",
                  static_cast<long long>(info.genus), static_cast<long long>(s->genus), info.components, !info.closed,
                  warn.empty() ? "none" : warn.c_str(), e.check.capped_rim_pairs);
      {
        // check_scan's fourth look: full split rims, walls under 0.65, both
        // facing; printed with the tube radii's ratio, so the 0.9 bound
        // shows its margin.
        dbss::RimOptions ro;
        ro.link = 1.5;
        ro.min_points = 6;
        const std::vector<dbss::PointRim> rims = dbss::link_rims(rp, ro);
        for (const auto& [i, j] : dbss::tube_end_pairs(rims, 0.65)) {
          const auto &a = rims[i], &b = rims[j];
          if (!dbss::rims_face_as_one_tube(a, b, 0.5)) continue;
          std::printf("  FULL %zu-%zu wall %.2f trr %.2f joins %d clear %.2f\n", i, j, 0.5 * (a.wall + b.wall),
                      std::min(a.tube_radius, b.tube_radius) / std::max(a.tube_radius, b.tube_radius),
                      dbss::surface_joins(test, a, b), dbss::gap_clearance(tree, a, b));
        }
      }
      for (double link : {1.25, 1.5}) {
        dbss::RimOptions ro;
        ro.link = link;
        ro.min_sectors = 3;
        ro.min_points = 5;
        const std::vector<dbss::PointRim> rims = dbss::link_rims(rp, ro);
        const auto tep = dbss::tube_end_pairs(rims);
        for (size_t i = 0; i < rims.size(); ++i) {
          const auto& q = rims[i];
          std::printf("  RIM link%.2f #%zu c(%.2f,%.2f,%.2f) ax(%.2f,%.2f,%.2f) r%.3f tr%.3f wall%.2f pts%zu sec%d\n", link, i,
                      q.centre[0], q.centre[1], q.centre[2], q.axis[0], q.axis[1], q.axis[2], q.radius, q.tube_radius, q.wall, q.points, q.sectors);
        }
        for (size_t i = 0; i < rims.size(); ++i)
          for (size_t j = i + 1; j < rims.size(); ++j) {
            const auto &a = rims[i], &b = rims[j];
            const V3 d = sub(b.centre, a.centre);
            const double gap = len(d);
            const double big = std::max(a.radius, b.radius), small = std::min(a.radius, b.radius);
            if (gap <= 0 || gap > 6 * big) continue;
            const V3 u{d[0] / gap, d[1] / gap, d[2] / gap};
            const bool paired = std::find(tep.begin(), tep.end(), std::pair{i, j}) != tep.end();
            const bool joins = dbss::surface_joins(test, a, b);
            const double clear = dbss::gap_clearance(tree, a, b);
            const Profile pax = profile(test, tree, a, b, a.axis, b.axis);
            const V3 ao = opening_of(rp, ro.link, a), bo = opening_of(rp, ro.link, b);
            const double oa = dot(u, ao), ob = -dot(u, bo);
            std::printf("  OPEN link%.2f %zu-%zu |oa| %.2f |ob| %.2f oa %.2f ob %.2f\n", link, i, j, len(ao), len(bo), oa, ob);
            std::printf("  PAIR link%.2f %zu-%zu%s gap/big %.2f size %.2f wall %.2f fa %.2f fb %.2f trr %.2f sec %d/%d joins %d clear %.2f | ax max %.2f mid %.2f in %d\n",
                        link, i, j, paired ? " TEP" : "", gap / big, small / big, 0.5 * (a.wall + b.wall), dot(u, a.axis),
                        dot(u, b.axis), std::min(a.tube_radius, b.tube_radius) / std::max(a.tube_radius, b.tube_radius),
                        a.sectors, b.sectors, joins, clear, pax.max_out, pax.mid_band, pax.inside);
          }
      }
      std::fflush(stdout);
    }
  }
  return 0;
}

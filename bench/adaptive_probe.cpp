// Would adaptive (non-uniform) refinement reach Draco qp11's error in 0.6x
// its bytes (issue 18)?  A measurement before any format change: no decoder
// does this today.
//
// The last level L of a mesh encoding refines every face of level L-1.
// Here it refines only some of them, red-green style: a refined ("red")
// face gets the odd vertices of its three edges and its four children; an
// unrefined face next to one refined neighbour is split in two ("green")
// by the shared edge's odd vertex, and one with two or more refined
// neighbours is refined as well (the closure, repeated until stable).
//
// Per face f of level L-1 the probe measures its share of the two-sided
// error against the input, at level L-1 and under its four children at
// level L:
//  - level -> input: the integral of the distance over f's area (f at
//    level L-1; its four children at level L), from `per_face` random
//    points, one in each of f's equal subtriangles, a quarter as many in
//    each child;
//  - input -> level: area-uniform samples of the input, each given to the
//    level-(L-1) face nearest it, with its distance to level L-1 and to
//    level L.
// The mixed surface's error is approximated by adding these per-face
// shares, the refined faces' at level L and the others' (green ones
// included) at level L-1: the level -> input mean is the sum of the chosen
// integrals over the sum of the chosen areas, the input -> level mean the
// chosen distances over the sample count.  Green faces are costed at level
// L-1, which should overstate their error (their split edge's odd vertex
// sits nearer the input than the flat face); --measure checks the sum
// against the built mixed mesh (-2.7%..+1.5% on armadillo and camel).
//
// Bits: a face's level-L values are those of its three edges.  Faces are
// refined in units: the faces of level L-1 under one face of level g
// (--units; g = L-1 is one face, g = 0 a control face).  A greedy pass
// orders the units by error removed per bit not yet paid (each value
// costed where the real coder puts it, spec 9b's adaptive model on today's
// full stream); then, for prefixes of that order, the closure is applied
// and the needed values are costed again as one stream in the canonical
// order without the others (as zero_probe does for implied zeros), plus
// one refine flag per unit at its ideal entropy n H(refined share).  The
// prefix is the real file's through level L-1 plus the level's chunk
// frame plus these bits.  With --draco, the last table gives dbss / Draco
// bytes at Draco's error: uniform (log-log between the targets' levels,
// as lod_bench's search lands) and adaptive (per unit level, with flags
// and with flags free).
//
//   adaptive_probe [--levels L] [--errors E1,E2,..] [--faces F] [--per-face 4|16] [--samples N]
//                  [--draco NAME:BYTES:ERROR,..] [--units G1,G2,..] [--check] [--measure] MESH
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <numeric>
#include <queue>
#include <random>
#include <sstream>
#include <string>
#include <unordered_map>
#include <vector>

#include "half_edge_edges.h"

#include "cut_holes.h"
#include "dbss/encoder/encode.h"
#include "dbss/encoder/encode_mesh.h"
#include "dbss/encoder/mesh_input.h"
#include "dbss/encoder/triangle_tree.h"
#include "dbss/io/geometry_files.h"
#include "dbss/measure/mesh_distance.h"
#include "dbss/measure/surface_samples.h"

using namespace dbss;

namespace {

// --check: a figure out of bounds makes the program exit 2 (the ctest).
bool g_failed = false;
// --measure: also build each mixed surface (red faces' children, green
// faces split in two, the rest as they are) and measure it with
// mesh_distance, to check the per-face approximation.
bool g_measure = false;
void expect(bool ok, const char* what) {
  if (!ok) std::fprintf(stderr, "adaptive_probe: check failed: %s\n", what), g_failed = true;
}

// Spec 9b's adaptive probability, costed ideally (-log2 of the coded bit's
// probability); zero_probe checks this model against the real coder.
struct Prob {
  uint32_t p = 16384;
  double code(uint32_t bit) {
    const double c = bit ? -std::log2((32768.0 - p) / 32768.0) : -std::log2(p / 32768.0);
    if (bit) p -= p >> 5;
    else p += (32768 - p) >> 5;
    return c;
  }
};

// Spec 9b's model over a level's values in order; returns each value's bits.
struct Model {
  Prob zero[7], sign[3], mag[7][14], expo[25];
  int32_t q1 = 0, q2 = 0;
  double code(int32_t v) {
    const uint32_t ctx = std::min<uint32_t>(std::abs(q1) + std::abs(q2), 6);
    const uint32_t s = q1 == 0 ? 0 : q1 > 0 ? 1 : 2;
    double bits = zero[ctx].code(v != 0);
    if (v != 0) {
      bits += sign[s].code(v < 0);
      const uint32_t m = std::abs(v);
      for (uint32_t j = 1; j <= 14; ++j) {
        if (j == m) { bits += mag[ctx][j - 1].code(0); break; }
        bits += mag[ctx][j - 1].code(1);
      }
      if (m >= 15) {
        const uint32_t x = m - 14;
        const int e = 31 - __builtin_clz(x);
        for (int k = 0; k < e; ++k) bits += expo[k].code(1);
        bits += expo[e].code(0) + e;
      }
    }
    q2 = q1, q1 = v;
    return bits;
  }
};

void corner(const std::vector<float>& P, uint32_t v, double out[3]) {
  for (int a = 0; a < 3; ++a) out[a] = P[3 * size_t{v} + a];
}

double area(const double a[3], const double b[3], const double c[3]) {
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
  return 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

// Subtriangles of the 4^k equal ones of a triangle (k = 0, 1, 2: 1, 4 or
// 16), each as its three corners (u, v) with the point a + u (b - a) + v (c - a).
struct Sub {
  double u[3], v[3];
};
std::vector<Sub> subtriangles(int per_face) {
  const int n = per_face >= 16 ? 4 : per_face >= 4 ? 2 : 1;  // subdivisions per side
  std::vector<Sub> out;
  for (int i = 0; i < n; ++i)
    for (int j = 0; i + j < n; ++j) {
      out.push_back({{double(i) / n, double(i + 1) / n, double(i) / n}, {double(j) / n, double(j) / n, double(j + 1) / n}});
      if (i + j + 1 < n)
        out.push_back({{double(i + 1) / n, double(i) / n, double(i + 1) / n},
                       {double(j) / n, double(j + 1) / n, double(j + 1) / n}});
    }
  return out;
}

// Which face of a mesh holds a point known to lie on its surface (a
// closest point): a hashed grid of the faces' boxes, the candidate nearest
// the query point `p` winning.
class FaceGrid {
 public:
  FaceGrid(const std::vector<float>& P, const std::vector<uint32_t>& T) : P_(P), T_(T) {
    const size_t nf = T.size() / 3;
    double len = 0;
    for (size_t f = 0; f < nf; ++f) {
      double a[3], b[3];
      corner(P, T[3 * f], a), corner(P, T[3 * f + 1], b);
      len += std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
    }
    cell_ = 2 * len / std::max<size_t>(nf, 1) + 1e-30;
    for (size_t f = 0; f < nf; ++f) {
      int64_t lo[3], hi[3];
      for (int a = 0; a < 3; ++a) {
        double mn = 1e300, mx = -1e300;
        for (int k = 0; k < 3; ++k) mn = std::min<double>(mn, P[3 * size_t{T[3 * f + k]} + a]), mx = std::max<double>(mx, P[3 * size_t{T[3 * f + k]} + a]);
        lo[a] = index(mn - 1e-6 * cell_), hi[a] = index(mx + 1e-6 * cell_);
      }
      for (int64_t x = lo[0]; x <= hi[0]; ++x)
        for (int64_t y = lo[1]; y <= hi[1]; ++y)
          for (int64_t z = lo[2]; z <= hi[2]; ++z) cells_[key(x, y, z)].push_back(uint32_t(f));
    }
  }
  // The face through `on` (a point of the surface) nearest `p`.
  uint32_t face(const double on[3], const double p[3]) const {
    auto it = cells_.find(key(index(on[0]), index(on[1]), index(on[2])));
    uint32_t best = 0;
    double bd = 1e300;
    if (it == cells_.end()) return best;
    for (uint32_t f : it->second) {
      double a[3], b[3], c[3];
      corner(P_, T_[3 * f], a), corner(P_, T_[3 * f + 1], b), corner(P_, T_[3 * f + 2], c);
      const double d = point_triangle_distance2(on, a, b, c) * 1e6 + point_triangle_distance2(p, a, b, c);
      if (d < bd) bd = d, best = f;
    }
    return best;
  }

 private:
  int64_t index(double x) const { return int64_t(std::floor(x / cell_)); }
  static uint64_t key(int64_t x, int64_t y, int64_t z) {
    return (uint64_t(x) & 0x1fffff) << 42 | (uint64_t(y) & 0x1fffff) << 21 | (uint64_t(z) & 0x1fffff);
  }
  const std::vector<float>& P_;
  const std::vector<uint32_t>& T_;
  double cell_ = 1;
  std::unordered_map<uint64_t, std::vector<uint32_t>> cells_;
};

struct Reference {
  std::string name;
  double bytes = 0, error = 0;
};

struct Point {
  size_t refined = 0, forced = 0, green = 0, values = 0;
  double value_bits = 0, flag_bits = 0, bytes = 0, error = 0;
  double measured = 0;  // --measure: the built mixed mesh's error
};

double entropy_bits(size_t k, size_t n) {
  if (k == 0 || k == n) return 0;
  const double p = double(k) / n;
  return -double(n) * (p * std::log2(p) + (1 - p) * std::log2(1 - p));
}

// Fewest bytes on a curve at `error` or below: its points, and log-log
// between two points in bytes order that straddle it; < 0 when the curve
// does not reach it.  `free_flags`: the flags' bits left out.
double bytes_at(std::vector<Point> c, double error, bool free_flags) {
  for (Point& p : c)
    if (free_flags) p.bytes -= p.flag_bits / 8;
  std::sort(c.begin(), c.end(), [](const Point& a, const Point& b) { return a.bytes < b.bytes; });
  double best = -1;
  for (size_t i = 0; i < c.size(); ++i) {
    double b = -1;
    if (c[i].error <= error) b = c[i].bytes;
    if (i > 0 && c[i].error <= error && c[i - 1].error > error) {
      const double t = std::log(c[i - 1].error / error) / std::log(c[i - 1].error / c[i].error);
      b = std::exp(std::log(c[i - 1].bytes) + t * std::log(c[i].bytes / c[i - 1].bytes));
    }
    if (b > 0 && (best < 0 || b < best)) best = b;
  }
  return best;
}

struct Summary {
  double target = 0;
  double uniform_bytes[2] = {}, uniform_error[2] = {};  // levels L-1 and L
  std::map<uint32_t, std::vector<Point>> curves;  // by refine unit level
};

Summary probe(const TriangleMesh& input, double diag, const TriangleTree& input_tree, const std::vector<double>& S,
              uint32_t levels, double target, uint32_t faces, int per_face,
              const std::vector<uint32_t>& unit_levels) {
  Summary out;
  out.target = target;
  EncodeOptions o;
  o.levels = levels;
  o.error = target;
  o.threads = 1;
  o.control.control_faces = faces;
  auto e = encode_mesh(input, o);
  if (!e.ok()) {
    std::fprintf(stderr, "%s\n", e.status().to_string().c_str());
    std::exit(1);
  }
  const Encoding& en = e.value().encoding;
  const uint32_t L = en.level_count;
  if (L < 1) std::exit(1);
  const auto& P3 = en.levels.positions[L - 1];
  const auto& T3 = en.levels.triangles[L - 1];
  const auto& P4 = en.levels.positions[L];
  const auto& T4 = en.levels.triangles[L];
  const std::vector<int32_t>& q = en.contents.levels[L - 1].q;
  const size_t nf = T3.size() / 3, V3 = P3.size() / 3;
  const std::vector<uint32_t> edge_of = half_edge_edges(T3);

  // Children of face f are faces 4f..4f+3 of level L: check it on the
  // corners (the parent's own corners and its edges' odd vertices).
  for (size_t f = 0; f < nf; ++f)
    for (int k = 0; k < 12; ++k) {
      const uint32_t v = T4[12 * f + k];
      bool ok = false;
      for (int j = 0; j < 3; ++j) ok = ok || v == T3[3 * f + j] || v == V3 + edge_of[3 * f + j];
      if (!ok) {
        std::fprintf(stderr, "face %zu: level %u's faces are not its children 4f..4f+3\n", f, L);
        std::exit(2);
      }
    }

  // Butterfly interpolates: level L keeps level L-1's vertices where they
  // were (the mixed surface takes its corners from level L's positions).
  expect(std::equal(P3.begin(), P3.end(), P4.begin()), "level L keeps level L-1's vertices");

  // level -> input, per face of level L-1: integral of the distance and
  // area, from one random point in each subtriangle (stratified: a fixed
  // point such as the centroid is biased, the farthest from a curved input).
  const auto sub3 = subtriangles(per_face), sub4 = subtriangles(std::max(1, per_face / 4));
  std::vector<double> I3(nf), A3(nf), I4(nf), A4(nf);
  std::mt19937 rng(11);
  auto integral = [&](const std::vector<float>& P, const uint32_t* t, const std::vector<Sub>& subs, double& I, double& A) {
    double a[3], b[3], c[3];
    corner(P, t[0], a), corner(P, t[1], b), corner(P, t[2], c);
    const double ar = area(a, b, c);
    double sum = 0;
    for (const Sub& st : subs) {
      const double s = std::sqrt(uniform01(rng)), r = uniform01(rng);
      const double w[3] = {1 - s, s * (1 - r), s * r};
      const double u = w[0] * st.u[0] + w[1] * st.u[1] + w[2] * st.u[2], v = w[0] * st.v[0] + w[1] * st.v[1] + w[2] * st.v[2];
      const double p[3] = {a[0] + u * (b[0] - a[0]) + v * (c[0] - a[0]), a[1] + u * (b[1] - a[1]) + v * (c[1] - a[1]),
                           a[2] + u * (b[2] - a[2]) + v * (c[2] - a[2])};
      sum += input_tree.distance(p);
    }
    I += ar * sum / subs.size();
    A += ar;
  };
  for (size_t f = 0; f < nf; ++f) {
    integral(P3, &T3[3 * f], sub3, I3[f], A3[f]);
    for (int k = 0; k < 4; ++k) integral(P4, &T4[3 * (4 * f + k)], sub4, I4[f], A4[f]);
  }

  // input -> level: each input sample to its nearest level-(L-1) face.
  const size_t ns = S.size() / 3;
  std::vector<double> S3(nf), S4(nf);
  {
    TriangleMesh m3{P3, T3}, m4{P4, T4};
    TriangleTree t3(m3), t4(m4);
    FaceGrid grid(P3, T3);
    for (size_t i = 0; i < ns; ++i) {
      double on[3];
      const double d3 = t3.closest_point(&S[3 * i], on);
      const uint32_t f = grid.face(on, &S[3 * i]);
      S3[f] += d3;
      S4[f] += t4.distance(&S[3 * i]);
    }
  }
  const double area3 = std::accumulate(A3.begin(), A3.end(), 0.0);
  auto mixed_error = [&](const std::vector<uint8_t>& red) {
    double I = 0, A = 0, s = 0;
    for (size_t f = 0; f < nf; ++f)
      if (red[f]) I += I4[f], A += A4[f], s += S4[f];
      else I += I3[f], A += A3[f], s += S3[f];
    return 0.5 * (I / A + s / ns) / diag;
  };
  {
    MeshDistanceOptions mo;
    mo.samples = 100000;
    mo.threads = 1;
    const double l3 = mesh_distance(TriangleMesh{P3, T3}, input, mo).mean() / diag;
    const double l4 = mesh_distance(TriangleMesh{P4, T4}, input, mo).mean() / diag;
    std::vector<uint8_t> none(nf, 0), all(nf, 1);
    std::printf("\n### target %g: %zu faces at level %u, %zu odd vertices at level %u; step %g\n", target, nf, L - 1,
                q.size(), L, en.step);
    std::printf("uniform levels, this probe's per-face sums against mesh_distance (100k samples): level %u %.3e / %.3e, "
                "level %u %.3e / %.3e\n",
                L - 1, mixed_error(none), l3, L, mixed_error(all), l4);
    // Different samples: within 10% on meshes of a few thousand faces.
    expect(std::abs(mixed_error(none) / l3 - 1) < 0.1, "level L-1's per-face sum is mesh_distance's");
    expect(std::abs(mixed_error(all) / l4 - 1) < 0.1, "level L's per-face sum is mesh_distance's");
  }

  // Each value's bits where today's coder puts it.
  std::vector<double> cost(q.size());
  double full_bits = 0;
  {
    Model m;
    for (size_t i = 0; i < q.size(); ++i) full_bits += cost[i] = m.code(q[i]);
  }
  const double frame = double(prefix_bytes(en, L) - prefix_bytes(en, L - 1)) - full_bits / 8;
  const double base = double(prefix_bytes(en, L - 1));
  out.uniform_bytes[0] = base, out.uniform_bytes[1] = double(prefix_bytes(en, L));

  // How concentrated the error is: the share of faces holding 50% and 80%
  // of level L-1's error, of the error level L removes, and the share of
  // level L's bits those faces' edges carry (half an edge's bits to each side).
  std::vector<double> err3(nf), gain(nf), bits_of(nf, 0.0);
  std::vector<uint32_t> faces_of_edge(q.size(), 0);
  for (size_t h = 0; h < T3.size(); ++h) ++faces_of_edge[edge_of[h]];
  for (size_t f = 0; f < nf; ++f) {
    err3[f] = 0.5 * (I3[f] / area3 + S3[f] / ns) / diag;
    gain[f] = 0.5 * ((I3[f] - I4[f]) / area3 + (S3[f] - S4[f]) / ns) / diag;
    for (int k = 0; k < 3; ++k) bits_of[f] += cost[edge_of[3 * f + k]] / faces_of_edge[edge_of[3 * f + k]];
  }
  auto share = [&](const std::vector<double>& w, double of) {
    std::vector<uint32_t> idx(nf);
    std::iota(idx.begin(), idx.end(), 0u);
    std::sort(idx.begin(), idx.end(), [&](uint32_t a, uint32_t b) { return w[a] > w[b]; });
    double total = 0, acc = 0, bits = 0;
    for (double x : w) total += std::max(x, 0.0);
    for (size_t i = 0; i < nf; ++i) {
      acc += std::max(w[idx[i]], 0.0), bits += bits_of[idx[i]];
      if (acc >= of * total) return std::pair{double(i + 1) / nf, bits / full_bits};
    }
    return std::pair{1.0, 1.0};
  };
  const auto e50 = share(err3, 0.5), e80 = share(err3, 0.8), g50 = share(gain, 0.5), g80 = share(gain, 0.8);
  size_t negative = 0;
  for (double g : gain) negative += g <= 0;
  std::printf("level %u's error: 50%% in %.1f%% of its faces (%.1f%% of level %u's bits below them), 80%% in %.1f%% (%.1f%%)\n",
              L - 1, 100 * e50.first, 100 * e50.second, L, 100 * e80.first, 100 * e80.second);
  std::printf("error level %u removes: 50%% in %.1f%% of the faces (%.1f%% of its bits), 80%% in %.1f%% (%.1f%%); "
              "%.1f%% of faces gain nothing or lose\n",
              L, 100 * g50.first, 100 * g50.second, 100 * g80.first, 100 * g80.second, 100.0 * negative / nf);

  // Face neighbours across edges, for the closure.
  std::vector<uint32_t> other(T3.size(), UINT32_MAX);
  {
    std::vector<uint32_t> first(q.size(), UINT32_MAX);
    for (size_t h = 0; h < T3.size(); ++h) {
      const uint32_t e2 = edge_of[h];
      if (first[e2] == UINT32_MAX) first[e2] = uint32_t(h);
      else other[h] = uint32_t(first[e2] / 3), other[first[e2]] = uint32_t(h / 3);
    }
  }
  out.uniform_error[0] = mixed_error(std::vector<uint8_t>(nf, 0));
  out.uniform_error[1] = mixed_error(std::vector<uint8_t>(nf, 1));

  // Refine units: the faces of level L-1 under one face of level g are
  // refined together, one flag each (g = L-1: a flag per face; g = 0: per
  // control face).  Greedy order of units: error removed per bit not yet
  // paid, lazily re-costed.
  for (uint32_t g : unit_levels) {
    if (g > L - 1) continue;
    const uint32_t shift = 2 * (L - 1 - g);
    const size_t nu = nf >> shift;
    std::vector<std::vector<uint32_t>> edges(nu);
    std::vector<double> ugain(nu, 0.0);
    for (size_t f = 0; f < nf; ++f) {
      ugain[f >> shift] += gain[f];
      for (int k = 0; k < 3; ++k) edges[f >> shift].push_back(edge_of[3 * f + k]);
    }
    for (auto& v : edges) std::sort(v.begin(), v.end()), v.erase(std::unique(v.begin(), v.end()), v.end());
    std::vector<uint8_t> paid(q.size(), 0), taken(nu, 0);
    auto unpaid = [&](size_t u) {
      double b = 0;
      for (uint32_t e2 : edges[u]) b += paid[e2] ? 0 : cost[e2];
      return b;
    };
    using Item = std::pair<double, uint32_t>;
    std::priority_queue<Item> heap;
    for (size_t u = 0; u < nu; ++u)
      if (ugain[u] > 0) heap.push({ugain[u] / std::max(unpaid(u), 1e-3), uint32_t(u)});
    std::vector<uint32_t> order;
    while (!heap.empty()) {
      auto [r, u] = heap.top();
      heap.pop();
      if (taken[u]) continue;
      const double now = ugain[u] / std::max(unpaid(u), 1e-3);
      if (now < r * (1 - 1e-12)) { heap.push({now, u}); continue; }
      taken[u] = 1, order.push_back(u);
      for (uint32_t e2 : edges[u]) paid[e2] = 1;
    }

    auto point = [&](size_t k) {
      std::vector<uint8_t> red(nf, 0);
      std::vector<uint32_t> work;  // faces whose neighbours changed
      for (size_t i = 0; i < k; ++i)
        for (size_t f = size_t{order[i]} << shift; f < (size_t{order[i]} + 1) << shift; ++f) red[f] = 1;
      for (size_t f = 0; f < nf; ++f)
        if (red[f])
          for (int j = 0; j < 3; ++j)
            if (other[3 * f + j] != UINT32_MAX && !red[other[3 * f + j]]) work.push_back(other[3 * f + j]);
      Point p;
      p.refined = k;
      while (!work.empty()) {
        const uint32_t f = work.back();
        work.pop_back();
        if (red[f]) continue;
        int n = 0;
        for (int j = 0; j < 3; ++j) n += other[3 * f + j] != UINT32_MAX && red[other[3 * f + j]];
        if (n < 2) continue;
        red[f] = 1, ++p.forced;
        for (int j = 0; j < 3; ++j)
          if (other[3 * f + j] != UINT32_MAX) work.push_back(other[3 * f + j]);
      }
      std::vector<uint8_t> need(q.size(), 0);
      for (size_t f = 0; f < nf; ++f) {
        if (red[f])
          for (int j = 0; j < 3; ++j) need[edge_of[3 * f + j]] = 1;
        else
          for (int j = 0; j < 3; ++j) p.green += other[3 * f + j] != UINT32_MAX && red[other[3 * f + j]];
      }
      Model m;
      for (size_t i = 0; i < q.size(); ++i)
        if (need[i]) p.value_bits += m.code(q[i]), ++p.values;
      p.flag_bits = entropy_bits(k, nu);
      p.bytes = base + frame + (p.value_bits + p.flag_bits) / 8;
      p.error = mixed_error(red);
      if (g_measure) {
        TriangleMesh mixed{P4, {}};
        for (size_t f = 0; f < nf; ++f) {
          if (red[f]) {
            mixed.triangles.insert(mixed.triangles.end(), &T4[12 * f], &T4[12 * f + 12]);
            continue;
          }
          int split = -1, n = 0;
          for (int j = 0; j < 3; ++j)
            if (other[3 * f + j] != UINT32_MAX && red[other[3 * f + j]]) split = j, ++n;
          const uint32_t* c = &T3[3 * f];
          if (n == 0) {
            mixed.triangles.insert(mixed.triangles.end(), c, c + 3);
          } else {  // green: (cj, m, cj+2) and (m, cj+1, cj+2)
            const uint32_t m2 = uint32_t(V3) + edge_of[3 * f + split];
            const uint32_t a = c[split], b = c[(split + 1) % 3], d = c[(split + 2) % 3];
            for (uint32_t v : {a, m2, d, m2, b, d}) mixed.triangles.push_back(v);
          }
        }
        MeshDistanceOptions mo;
        mo.samples = 100000;
        p.measured = mesh_distance(mixed, input, mo).mean() / diag;
        // Green faces count at level L-1 in the approximation, so it runs
        // high; by more than a few percent it would not be worth reading.
        expect(std::abs(p.measured / p.error - 1) < 0.15, "the per-face sum is within 15% of the built mixed mesh's error");
      }
      return p;
    };
    std::printf("\nrefine units: the faces under one face of level %u (%zu units of %zu faces)\n", g, nu, size_t{1} << shift);
    std::printf("\n| units refined (greedy) | faces + closure | green edges | odd vertices | value bits | flag bits | prefix bytes (flags free) | two-sided error |\n"
                "|---|---|---|---|---|---|---|---|\n");
    std::printf("| uniform level %u | | | 0 | 0 | 0 | %.0f | %.3e |\n", L - 1, base, out.uniform_error[0]);
    const double fractions[] = {0.01, 0.02, 0.05, 0.1, 0.15, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0};
    std::vector<Point>& curve = out.curves[g];
    for (double fr : fractions) {
      const size_t k = size_t(std::llround(fr * order.size()));
      const Point p = point(k);
      curve.push_back(p);
      std::printf("| %zu (%.0f%%) | %zu | %zu | %zu | %.0f | %.0f | %.0f (%.0f) | %.3e", p.refined, 100.0 * p.refined / nu,
                  p.forced, p.green, p.values, p.value_bits, p.flag_bits, p.bytes, p.bytes - p.flag_bits / 8, p.error);
      if (g_measure) std::printf(" (built: %.3e)", p.measured);
      std::printf(" |\n");
      if (g_measure) curve.back().error = p.measured;  // the summary from the built meshes
    }
    std::printf("| uniform level %u | | | %zu | %.0f | 0 | %.0f | %.3e |\n", L, q.size(), full_bits, out.uniform_bytes[1],
                out.uniform_error[1]);
    // The greedy curve starts at level L-1 and falls below it; its units all gain.
    expect(std::all_of(curve.begin(), curve.end(), [&](const Point& p) { return p.error <= out.uniform_error[0] * (1 + 1e-9); }),
           "refining units that gain lowers the error");
    expect(order.empty() || std::min_element(curve.begin(), curve.end(), [](auto& a, auto& b) { return a.error < b.error; })
                                    ->error < out.uniform_error[0], "the curve ends below level L-1's error");
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  uint32_t levels = 4, faces = 0;
  bool check = false;
  int per_face = 16;
  size_t samples = 200000;
  std::vector<double> targets{1.3e-4};
  std::vector<uint32_t> units;  // refine unit levels; default L-1 and 0
  std::vector<Reference> refs;
  std::string path;
  auto usage = [] {
    std::fprintf(stderr, "usage: adaptive_probe [--levels L] [--errors E1,E2,..] [--faces F] [--per-face 4|16] "
                         "[--samples N] [--draco NAME:BYTES:ERROR,..] [--units G1,G2,..] [--check] [--measure] MESH\n");
    return 2;
  };
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool value = i + 1 < argc;
    if (a == "--levels" && value) levels = std::atoi(argv[++i]);
    else if (a == "--faces" && value) faces = std::atoi(argv[++i]);
    else if (a == "--per-face" && value) per_face = std::atoi(argv[++i]);
    else if (a == "--check") check = true;
    else if (a == "--measure") g_measure = true;
    else if (a == "--units" && value) {
      std::stringstream s(argv[++i]);
      for (std::string t; std::getline(s, t, ',');) units.push_back(std::atoi(t.c_str()));
    }
    else if (a == "--samples" && value) samples = std::atol(argv[++i]);
    else if (a == "--errors" && value) {
      targets.clear();
      std::stringstream s(argv[++i]);
      for (std::string t; std::getline(s, t, ',');) targets.push_back(std::atof(t.c_str()));
    } else if (a == "--draco" && value) {
      std::stringstream s(argv[++i]);
      for (std::string t; std::getline(s, t, ',');) {
        Reference r;
        const size_t c1 = t.find(':'), c2 = t.rfind(':');
        if (c1 == std::string::npos || c1 == c2) return usage();
        r.name = t.substr(0, c1), r.bytes = std::atof(t.substr(c1 + 1, c2 - c1 - 1).c_str());
        r.error = std::atof(t.substr(c2 + 1).c_str());
        refs.push_back(r);
      }
    } else if (a.empty() || a[0] == '-') return usage();
    else path = a;
  }
  if (path.empty() || levels < 1 || targets.empty()) return usage();
  if (units.empty()) units = {levels - 1, 0};
  auto read = read_mesh(path);
  if (!read.ok()) return std::fprintf(stderr, "adaptive_probe: %s: %s\n", path.c_str(), read.status().to_string().c_str()), 77;
  auto prepared = prepare_mesh_input(read.value());
  if (!prepared.ok()) return std::fprintf(stderr, "adaptive_probe: %s: %s\n", path.c_str(), prepared.status().to_string().c_str()), 1;
  const TriangleMesh& input = prepared.value();
  const double diag = bench::diagonal(input);
  const TriangleTree tree(input);
  const std::vector<double> S = sample_surface(input, samples, 7);
  std::printf("## %s: %zu triangles; adaptive last level (probe: %d points a face, %zu input samples)\n", path.c_str(),
              input.triangle_count(), per_face, samples);

  std::vector<Summary> runs;
  for (double t : targets) runs.push_back(probe(input, diag, tree, S, levels, t, faces, per_face, units));

  if (!refs.empty()) {
    std::printf("\n| Draco | bytes | error | uniform dbss / Draco (best target, level; log-log between targets) |");
    for (uint32_t g : units) std::printf(" adaptive, unit level %u / Draco (target) | flags free |", g);
    std::printf("\n|---|---|---|---|");
    for (size_t i = 0; i < units.size(); ++i) std::printf("---|---|");
    std::printf("\n");
    for (const Reference& r : refs) {
      double uni = -1, uni_t = 0;
      int uni_l = 0;
      for (const Summary& s : runs)
        for (int l = 0; l < 2; ++l)
          if (s.uniform_error[l] <= r.error && (uni < 0 || s.uniform_bytes[l] < uni))
            uni = s.uniform_bytes[l], uni_t = s.target, uni_l = l;
      // The uniform levels of every target as one curve, log-log between
      // them as lod_bench's search would land (within its 2%).
      std::vector<Point> uc;
      for (const Summary& s : runs)
        for (int l = 0; l < 2; ++l) {
          Point p;
          p.bytes = s.uniform_bytes[l], p.error = s.uniform_error[l];
          uc.push_back(p);
        }
      const double between = bytes_at(uc, r.error, false);
      char u[96] = "not reached";
      if (uni > 0)
        std::snprintf(u, sizeof u, "%.2f (%g, L%s); between targets %.2f", uni / r.bytes, uni_t, uni_l ? "" : "-1",
                      between / r.bytes);
      std::printf("| %s | %.0f | %.2e | %s |", r.name.c_str(), r.bytes, r.error, u);
      for (uint32_t g : units)
        for (bool free_flags : {false, true}) {
          double ada = -1, ada_t = 0;
          for (const Summary& s : runs) {
            auto it = s.curves.find(g);
            if (it == s.curves.end()) continue;
            const double b = bytes_at(it->second, r.error, free_flags);
            if (b > 0 && (ada < 0 || b < ada)) ada = b, ada_t = s.target;
          }
          if (ada > 0) std::printf(" %.2f (%g) |", ada / r.bytes, ada_t);
          else std::printf(" not reached |");
        }
      std::printf("\n");
    }
  }
  return check && g_failed ? 2 : 0;
}

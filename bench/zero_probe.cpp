// What zeros cost in LEVL coding 2 and what a format change for them would
// save (issue 18).  Per level: the share of zeros and small values, and the
// ideal bits (-log2 P under spec 9b's own adaptive model) split into the
// zero decision of zeros, the zero decision of non-zeros, signs and
// magnitudes.  Then two format changes simulated on the same values:
//  - a per-face "stop refining" flag (every odd vertex on the face's edges
//    and below it is zero), coded for the faces of levels `first`..L-1
//    whose parent is not stopped, with an adaptive probability per
//    (previous face's flag, how many of its corners carry a non-zero q of
//    their own level); the implied zeros are left out of the stream;
//  - a geometric context a decoder could compute before a level's values:
//    how far the butterfly point sits off its edge's chord, in steps
//    (zero decision by its size, sign by its sign).
// And (sixteenth session) contexts from the spatial neighbours a decoder has
// already read: the level's edges that share a triangle with this one and
// come before it, or the edge's end vertices' own values at the level
// before; a few context sets over the same values, the first of them spec
// 9b's own (checked to cost what the model costs).
// The ideal costing is checked against the encoder's real coding-2 chunks
// (exit 2 when a level differs by more than 0.2% + 6 bytes: the flush
// adds about 4; a model adapting at 1/16 instead of 1/32 is 1% off), so the
// simulations start from the coder the files use.
//   zero_probe [--levels L] [--error E] [--faces F] [--rdo LAMBDA] MESH
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <unordered_map>
#include <vector>

#include "half_edge_edges.h"

#include "dbss/encoder/encode_mesh.h"
#include "dbss/encoder/mesh_input.h"
#include "dbss/io/geometry_files.h"

using namespace dbss;

namespace {

// Spec 9b's adaptive probability, costed ideally (-log2 of the coded bit's
// probability) instead of range coded: within a few bytes of the real coder.
struct Prob {
  uint32_t p = 16384;
  double code(uint32_t bit) {
    const double c = bit ? -std::log2((32768.0 - p) / 32768.0) : -std::log2(p / 32768.0);
    if (bit) p -= p >> 5;
    else p += (32768 - p) >> 5;
    return c;
  }
};

struct Costs {
  double zero_of_zeros = 0, zero_of_nonzeros = 0, sign = 0, magnitude = 0;
  double total() const { return zero_of_zeros + zero_of_nonzeros + sign + magnitude; }
};

// Spec 9b's model over `q` in order, costs split by kind.
struct Model {
  Prob zero[7], sign[3], mag[7][14], expo[25];
  int32_t q1 = 0, q2 = 0;
  void code(int32_t v, Costs& c) {
    const uint32_t ctx = std::min<uint32_t>(std::abs(q1) + std::abs(q2), 6);
    const uint32_t s = q1 == 0 ? 0 : q1 > 0 ? 1 : 2;
    if (v == 0) {
      c.zero_of_zeros += zero[ctx].code(0);
    } else {
      c.zero_of_nonzeros += zero[ctx].code(1);
      c.sign += sign[s].code(v < 0);
      const uint32_t m = std::abs(v);
      for (uint32_t j = 1; j <= 14; ++j) {
        if (j == m) { c.magnitude += mag[ctx][j - 1].code(0); break; }
        c.magnitude += mag[ctx][j - 1].code(1);
      }
      if (m >= 15) {
        const uint32_t x = m - 14;
        const int e = 31 - __builtin_clz(x);
        for (int k = 0; k < e; ++k) c.magnitude += expo[k].code(1);
        c.magnitude += expo[e].code(0) + e;
      }
    }
    q2 = q1, q1 = v;
  }
};

}  // namespace

int main(int argc, char** argv) {
  uint32_t levels = 4;
  double error = 1.3e-4;
  uint32_t faces = 0;
  double rdo = 0;
  std::string path;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    const bool value = i + 1 < argc;
    if (a == "--levels" && value) levels = std::atoi(argv[++i]);
    else if (a == "--error" && value) error = std::atof(argv[++i]);
    else if (a == "--faces" && value) faces = std::atoi(argv[++i]);
    else if (a == "--rdo" && value) rdo = std::atof(argv[++i]);
    else if (a.empty() || a[0] == '-')
      return std::fprintf(stderr, "usage: zero_probe [--levels L] [--error E] [--faces F] [--rdo LAMBDA] MESH\n"), 2;
    else path = a;
  }
  auto in = read_mesh(path);
  if (!in.ok()) return std::fprintf(stderr, "zero_probe: %s: %s\n", path.c_str(), in.status().to_string().c_str()), 77;
  EncodeOptions o;
  o.levels = levels;
  o.error = error;
  o.threads = 1;
  o.control.control_faces = faces;
  MeshEncodeOptions mo;
  mo.rdo_lambda = rdo;
  mo.rdo_first_level = levels;
  auto e = encode_mesh(in.value(), o, mo);
  if (!e.ok()) { std::fprintf(stderr, "%s\n", e.status().to_string().c_str()); return 1; }
  const Encoding& en = e.value().encoding;
  const uint32_t L = en.level_count;
  std::printf("%s: %zu bytes, control %zu triangles, error target %g, step %g\n", path.c_str(), en.bytes.size(),
              en.levels.triangles[0].size() / 3, error, en.step);

  // q[l] (l = 1..L): level l's values, one per edge of level l-1.
  std::vector<std::vector<int32_t>> q(L + 1);
  std::vector<std::vector<uint32_t>> edge_of(L + 1);  // edge_of[m]: half-edge -> edge of level m
  for (uint32_t l = 1; l <= L; ++l) q[l] = en.contents.levels[l - 1].q;
  for (uint32_t m = 0; m < L; ++m) edge_of[m] = half_edge_edges(en.levels.triangles[m]);

  std::printf("\n| level | odd | zeros | abs 1 | abs 2 | abs > 2 | chunk bytes | bits/odd | zero flags of zeros | of non-zeros | signs | magnitudes |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  double all_bits = 0;
  std::vector<double> level_bits(L + 1);
  for (uint32_t l = 1; l <= L; ++l) {
    size_t n[4] = {};
    for (int32_t v : q[l]) ++n[std::min<uint32_t>(std::abs(v), 3)];
    Model m;
    Costs c;
    for (int32_t v : q[l]) m.code(v, c);
    const double odd = double(q[l].size());
    level_bits[l] = c.total();
    all_bits += c.total();
    const auto& chunk = en.levels.chunks[l - 1];
    if (en.contents.levels[l - 1].coding == format::DisplacementCoding::context &&
        std::abs(c.total() / 8 - double(chunk.size() - 16)) > 0.002 * double(chunk.size()) + 6) {
      std::fprintf(stderr, "level %u: ideal %.0f bytes, coder %zu: the model here is not spec 9b's\n", l,
                   c.total() / 8, chunk.size() - 16);
      return 2;
    }
    std::printf("| %u | %zu | %.1f%% | %.1f%% | %.1f%% | %.1f%% | %zu | %.3f | %.1f%% | %.1f%% | %.1f%% | %.1f%% |\n", l,
                q[l].size(), 100 * n[0] / odd, 100 * n[1] / odd, 100 * n[2] / odd, 100 * n[3] / odd,
                en.levels.chunks[l - 1].size(), c.total() / odd, 100 * c.zero_of_zeros / c.total(),
                100 * c.zero_of_nonzeros / c.total(), 100 * c.sign / c.total(), 100 * c.magnitude / c.total());
  }

  // dead[m][f]: every odd vertex of levels m+1..L on f's edges or below f is zero.
  std::vector<std::vector<uint8_t>> dead(L);
  for (int m = int(L) - 1; m >= 0; --m) {
    const size_t nf = en.levels.triangles[m].size() / 3;
    dead[m].assign(nf, 0);
    for (size_t f = 0; f < nf; ++f) {
      bool d = true;
      for (int k = 0; k < 3 && d; ++k) d = q[m + 1][edge_of[m][3 * f + k]] == 0;
      for (int k = 0; k < 4 && d && m + 1 < int(L); ++k) d = dead[m + 1][4 * f + k];
      dead[m][f] = d;
    }
  }
  std::printf("\nfaces whose whole subtree is zero (share of the level's faces): ");
  for (uint32_t m = 0; m < L; ++m) {
    size_t d = 0;
    for (auto x : dead[m]) d += x;
    std::printf("level %u %.1f%%  ", m, 100.0 * d / dead[m].size());
  }
  std::printf("\n");

  // Simulated coder: flags on faces of levels first..L-1 (those whose parent
  // is not flagged dead), coded in LEVL m+1 before its values with one
  // adaptive probability per context (how many of the face's three edge
  // neighbours at level m were coded dead before it: 0..3, else 4 = parent
  // level had no flags); values implied zero left out of the stream.
  std::printf("\n| flags from level | flag bits | values left | value bits | total bits | vs today | per level (today -> with flags, bits/odd) |\n|---|---|---|---|---|---|---|\n");
  for (uint32_t first = 0; first < L; ++first) {
    double flag_bits = 0, value_bits = 0;
    size_t left = 0;
    std::string per;
    for (uint32_t m = 0; m < L; ++m) {
      const size_t nf = dead[m].size();
      // covered: face under a dead flagged face (itself flagged dead or its ancestor)
      std::vector<uint8_t> covered(nf, 0);
      double fb = 0;
      if (m >= first) {
        Prob ctx[2][5];
        const auto& Tm = en.levels.triangles[m];
        const size_t Vprev = m > 0 ? en.levels.positions[m - 1].size() / 3 : 0;
        for (size_t f = 0; f < nf; ++f) {
          const bool parent_dead = m > first && dead[m - 1][f / 4];
          if (parent_dead) { covered[f] = 1; continue; }
          // context: the previous face's flag in face order, and how many
          // of the face's corners are odd vertices of level m with q != 0
          // (4: level 0, no q); the decoder knows both before the flag.
          int corners = m == 0 ? 4 : 0;
          for (int k = 0; k < 3 && m > 0; ++k) {
            const uint32_t v = Tm[3 * f + k];
            corners += v >= Vprev && q[m][v - Vprev] != 0;
          }
          const int c0 = f > 0 && dead[m][f - 1] ? 1 : 0;
          auto& cp = ctx[c0][corners];
          fb += cp.code(dead[m][f]);
          covered[f] = dead[m][f];
        }
      }
      std::vector<uint8_t> implied(q[m + 1].size(), 0);
      const auto& T = en.levels.triangles[m];
      for (size_t f = 0; f < T.size() / 3; ++f)
        if (covered[f])
          for (int k = 0; k < 3; ++k) implied[edge_of[m][3 * f + k]] = 1;
      Model model;
      Costs c;
      size_t lv = 0;
      for (size_t i = 0; i < q[m + 1].size(); ++i)
        if (!implied[i]) model.code(q[m + 1][i], c), ++lv;
      flag_bits += fb, value_bits += c.total(), left += lv;
      char buf[96];
      std::snprintf(buf, sizeof buf, " L%u %.3f->%.3f", m + 1, level_bits[m + 1] / q[m + 1].size(),
                    (fb + c.total()) / q[m + 1].size());
      per += buf;
    }
    std::printf("| %u | %.0f | %zu | %.0f | %.0f | %.1f%% |%s |\n", first, flag_bits, left, value_bits,
                flag_bits + value_bits, 100 * (flag_bits + value_bits - all_bits) / all_bits, per.c_str());
  }

  // A geometric context (what a decoder could compute before level l's
  // values): the butterfly point's offset from its edge's chord midpoint
  // along the normal, c = (p0 - mid) . n, in steps.  n here is the mean of
  // the edge's two face normals and p0 = the decoded odd vertex - q step n,
  // an estimate for this measurement only.  Zero decision by (today's
  // context, |c| bucket), sign by (today's, sign of c).
  std::printf("\n| level | today bits/odd | with |c| for zero, sign(c) for sign | zero bits | sign bits | P(sign = -sign c) |\n|---|---|---|---|---|---|\n");
  double geo_all = 0;
  for (uint32_t m = 0; m < L; ++m) {
    const auto& T = en.levels.triangles[m];
    const auto& P = en.levels.positions[m];
    const auto& P1 = en.levels.positions[m + 1];
    const size_t V = P.size() / 3;
    const double step = en.contents.levels[m].step;
    std::vector<double> nrm(3 * q[m + 1].size(), 0.0), mid(3 * q[m + 1].size(), 0.0);
    for (size_t f = 0; f < T.size() / 3; ++f) {
      const float* a = &P[3 * size_t{T[3 * f]}];
      const float* b = &P[3 * size_t{T[3 * f + 1]}];
      const float* c = &P[3 * size_t{T[3 * f + 2]}];
      const double u[3] = {double(b[0]) - a[0], double(b[1]) - a[1], double(b[2]) - a[2]};
      const double v[3] = {double(c[0]) - a[0], double(c[1]) - a[1], double(c[2]) - a[2]};
      double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
      const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      if (len > 0) for (double& x : n) x /= len;
      for (int k = 0; k < 3; ++k) {
        const uint32_t e = edge_of[m][3 * f + k];
        const uint32_t i0 = T[3 * f + k], i1 = T[3 * f + (k + 1) % 3];
        for (int d = 0; d < 3; ++d) nrm[3 * e + d] += n[d], mid[3 * e + d] = 0.5 * (double(P[3 * i0 + d]) + P[3 * i1 + d]);
      }
    }
    Prob zero[7][6], sign[3][3], zero0[7], sign0[3];
    double zb = 0, sb = 0, zb0 = 0, sb0 = 0;
    size_t against = 0, nz = 0;
    int32_t q1 = 0, q2 = 0;
    for (size_t e = 0; e < q[m + 1].size(); ++e) {
      double* n = &nrm[3 * e];
      const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      double c = 0;
      const int32_t v = q[m + 1][e];
      if (len > 0) {
        for (int d = 0; d < 3; ++d) c += (P1[3 * (V + e) + d] - mid[3 * e + d]) * n[d] / len;
        c = c / step - v;
      }
      const double ac = std::abs(c);
      const int bucket = ac < 0.25 ? 0 : ac < 0.5 ? 1 : ac < 1 ? 2 : ac < 2 ? 3 : ac < 4 ? 4 : 5;
      const int cs = c > 0.05 ? 1 : c < -0.05 ? 2 : 0;
      const uint32_t ctx = std::min<uint32_t>(std::abs(q1) + std::abs(q2), 6);
      const uint32_t s = q1 == 0 ? 0 : q1 > 0 ? 1 : 2;
      zb += zero[ctx][bucket].code(v != 0);
      zb0 += zero0[ctx].code(v != 0);
      if (v != 0) {
        sb += sign[s][cs].code(v < 0);
        sb0 += sign0[s].code(v < 0);
        ++nz;
        against += (v > 0) != (c > 0);
      }
      q2 = q1, q1 = v;
    }
    const double odd = double(q[m + 1].size());
    const double geo = level_bits[m + 1] - zb0 - sb0 + zb + sb;
    geo_all += geo;
    std::printf("| %u | %.3f | %.3f (%+.1f%%) | %.0f -> %.0f | %.0f -> %.0f | %.2f |\n", m + 1, level_bits[m + 1] / odd,
                geo / odd, 100 * (geo - level_bits[m + 1]) / level_bits[m + 1], zb0, zb, sb0, sb,
                double(against) / std::max<size_t>(nz, 1));
  }
  std::printf("geometric contexts, all levels: %.0f bytes (%+.1f%%)\n", geo_all / 8, 100 * (geo_all - all_bits) / all_bits);

  // Spatial neighbours (sixteenth session): the values a decoder has already
  // read on the level's edges that share a triangle with this one (lower
  // edge ids: up to four), S their sum and A their absolute sum.
  //  - context: zero decision by (today's context, min(A, 4)), sign by
  //    (today's, sign of S), magnitudes as today;
  //  - prediction: r = q - round(S / count) coded with today's model;
  //  - parents: the edge's two end vertices' own q when they are odd
  //    vertices of the level before (0 for even ends), P their sum: zero
  //    by (today's, min(|P|, 4)), sign by (today's, sign of P).
  std::printf("\n| level | today bits/odd | neighbour context | prediction from neighbours | parent-end context | both contexts | P(sign q = sign S), q and S non-zero |\n|---|---|---|---|---|---|---|\n");
  double nb_all[4] = {};
  for (uint32_t m = 0; m < L; ++m) {
    const auto& T = en.levels.triangles[m];
    const size_t E = q[m + 1].size();
    const size_t Vprev = m > 0 ? en.levels.positions[m - 1].size() / 3 : 0, V = en.levels.positions[m].size() / 3;
    std::vector<std::vector<uint32_t>> nb(E);
    std::vector<std::array<uint32_t, 2>> ends(E);
    for (size_t f = 0; f < T.size() / 3; ++f)
      for (int k = 0; k < 3; ++k) {
        const uint32_t e = edge_of[m][3 * f + k];
        ends[e] = {T[3 * f + k], T[3 * f + (k + 1) % 3]};
        for (int j = 1; j < 3; ++j) {
          const uint32_t o2 = edge_of[m][3 * f + (k + j) % 3];
          if (o2 < e && std::find(nb[e].begin(), nb[e].end(), o2) == nb[e].end()) nb[e].push_back(o2);
        }
      }
    auto parent_q = [&](uint32_t v) { return m > 0 && v >= Vprev && v < V ? q[m][v - Vprev] : 0; };
    Model pred_model;
    Costs pred_costs;
    Prob z1[7][5], s1[3][3], z2[7][5], s2[3][3], z3[7][5][5], s3[3][3][3], mag[7][14], expo[25];
    double b1 = 0, b2 = 0, b3 = 0, mb = 0;
    size_t agree = 0, both = 0;
    int32_t q1 = 0, q2 = 0;
    for (size_t e = 0; e < E; ++e) {
      const int32_t v = q[m + 1][e];
      int32_t S = 0, A = 0;
      for (uint32_t o2 : nb[e]) S += q[m + 1][o2], A += std::abs(q[m + 1][o2]);
      const int32_t P = parent_q(ends[e][0]) + parent_q(ends[e][1]);
      const double mean = nb[e].empty() ? 0.0 : double(S) / double(nb[e].size());
      pred_model.code(v - static_cast<int32_t>(std::lround(mean)), pred_costs);
      const uint32_t ctx = std::min<uint32_t>(std::abs(q1) + std::abs(q2), 6);
      const uint32_t s = q1 == 0 ? 0 : q1 > 0 ? 1 : 2;
      const uint32_t a = std::min<int32_t>(A, 4), pa = std::min<int32_t>(std::abs(P), 4);
      const uint32_t ss = S == 0 ? 0 : S > 0 ? 1 : 2, ps = P == 0 ? 0 : P > 0 ? 1 : 2;
      b1 += z1[ctx][a].code(v != 0);
      b2 += z2[ctx][pa].code(v != 0);
      b3 += z3[ctx][a][pa].code(v != 0);
      if (v != 0) {
        b1 += s1[s][ss].code(v < 0);
        b2 += s2[s][ps].code(v < 0);
        b3 += s3[s][ss][ps].code(v < 0);
        if (S != 0) ++both, agree += (v > 0) == (S > 0);
        const uint32_t mm = std::abs(v);
        for (uint32_t j = 1; j <= 14; ++j) {
          if (j == mm) { mb += mag[ctx][j - 1].code(0); break; }
          mb += mag[ctx][j - 1].code(1);
        }
        if (mm >= 15) {
          const uint32_t x = mm - 14;
          const int ex = 31 - __builtin_clz(x);
          for (int k = 0; k < ex; ++k) mb += expo[k].code(1);
          mb += expo[ex].code(0) + ex;
        }
      }
      q2 = q1, q1 = v;
    }
    const double odd = double(E), today = level_bits[m + 1];
    const double r[4] = {b1 + mb, pred_costs.total(), b2 + mb, b3 + mb};
    for (int k = 0; k < 4; ++k) nb_all[k] += r[k];
    std::printf("| %u | %.3f |", m + 1, today / odd);
    for (int k = 0; k < 4; ++k) std::printf(" %.3f (%+.1f%%) |", r[k] / odd, 100 * (r[k] - today) / today);
    std::printf(" %.2f |\n", double(agree) / std::max<size_t>(both, 1));
  }
  // Context variants over the same features (ids: zero, sign, magnitude
  // context of each value), to see how far the neighbours' values go.
  struct Feat { int32_t v, c, s, A, S, k; };
  struct Variant { const char* name; int (*zero)(const Feat&); int (*sign)(const Feat&); int (*mag)(const Feat&); };
  static const Variant variants[] = {
      {"today (seq)", [](const Feat& f) { return f.c; }, [](const Feat& f) { return f.s; }, [](const Feat& f) { return f.c; }},
      {"V1 z(c,A4) s(s,sgnS)", [](const Feat& f) { return f.c * 8 + std::min(f.A, 4); },
       [](const Feat& f) { return f.s * 3 + (f.S > 0 ? 1 : f.S < 0 ? 2 : 0); }, [](const Feat& f) { return f.c; }},
      {"V2 z(c,A6) s(s,S+-3) m(c,A3)", [](const Feat& f) { return f.c * 8 + std::min(f.A, 6); },
       [](const Feat& f) { return f.s * 8 + std::clamp(f.S, -3, 3) + 3; }, [](const Feat& f) { return f.c * 4 + std::min(f.A, 3); }},
      {"V3 z(min(c,3),A6,k) s(S+-3) m(min(c+A,6))", [](const Feat& f) { return (std::min(f.c, 3) * 8 + std::min(f.A, 6)) * 5 + f.k; },
       [](const Feat& f) { return std::clamp(f.S, -3, 3) + 3; }, [](const Feat& f) { return std::min(f.c + f.A, 6); }},
      {"V4 z(c,A6,k) s(s,S+-3,k) m(c,A3)", [](const Feat& f) { return (f.c * 8 + std::min(f.A, 6)) * 5 + f.k; },
       [](const Feat& f) { return (f.s * 8 + std::clamp(f.S, -3, 3) + 3) * 5 + f.k; }, [](const Feat& f) { return f.c * 4 + std::min(f.A, 3); }},
  };
  constexpr size_t kVariants = sizeof variants / sizeof variants[0];
  std::vector<double> var_all(kVariants, 0.0);
  std::printf("\n| level |");
  for (const Variant& v : variants) std::printf(" %s |", v.name);
  std::printf("\n|---|");
  for (size_t i = 0; i < kVariants; ++i) std::printf("---|");
  std::printf("\n");
  for (uint32_t m = 0; m < L; ++m) {
    const auto& T = en.levels.triangles[m];
    const size_t E = q[m + 1].size();
    std::vector<std::vector<uint32_t>> nb(E);
    for (size_t f = 0; f < T.size() / 3; ++f)
      for (int k = 0; k < 3; ++k) {
        const uint32_t e = edge_of[m][3 * f + k];
        for (int j = 1; j < 3; ++j) {
          const uint32_t o2 = edge_of[m][3 * f + (k + j) % 3];
          if (o2 < e && std::find(nb[e].begin(), nb[e].end(), o2) == nb[e].end()) nb[e].push_back(o2);
        }
      }
    std::vector<Feat> feats(E);
    int32_t q1 = 0, q2 = 0;
    for (size_t e = 0; e < E; ++e) {
      Feat& f = feats[e];
      f.v = q[m + 1][e];
      f.c = std::min<int32_t>(std::abs(q1) + std::abs(q2), 6);
      f.s = q1 == 0 ? 0 : q1 > 0 ? 1 : 2;
      f.A = f.S = 0;
      for (uint32_t o2 : nb[e]) f.S += q[m + 1][o2], f.A += std::abs(q[m + 1][o2]);
      f.k = std::min<int32_t>(static_cast<int32_t>(nb[e].size()), 4);
      q2 = q1, q1 = f.v;
    }
    std::printf("| %u |", m + 1);
    for (size_t vi = 0; vi < kVariants; ++vi) {
      std::unordered_map<int, Prob> zero, sign;
      std::unordered_map<int, std::array<Prob, 14>> mag;
      Prob expo[25];
      double bits = 0;
      for (const Feat& f : feats) {
        bits += zero[variants[vi].zero(f)].code(f.v != 0);
        if (f.v == 0) continue;
        bits += sign[variants[vi].sign(f)].code(f.v < 0);
        auto& mg = mag[variants[vi].mag(f)];
        const uint32_t mm = std::abs(f.v);
        for (uint32_t j = 1; j <= 14; ++j) {
          if (j == mm) { bits += mg[j - 1].code(0); break; }
          bits += mg[j - 1].code(1);
        }
        if (mm >= 15) {
          const uint32_t x = mm - 14;
          const int ex = 31 - __builtin_clz(x);
          for (int k = 0; k < ex; ++k) bits += expo[k].code(1);
          bits += expo[ex].code(0) + ex;
        }
      }
      var_all[vi] += bits;
      // The first variant is spec 9b's own contexts: it must cost what the
      // model above costs, or the harness is not measuring the same coder.
      if (vi == 0 && std::abs(bits - level_bits[m + 1]) > 1e-6 * level_bits[m + 1] + 1e-6) {
        std::fprintf(stderr, "level %u: the variants' harness costs today's contexts at %.1f bits, the model at %.1f\n", m + 1,
                     bits, level_bits[m + 1]);
        return 2;
      }
      std::printf(" %.3f (%+.1f%%) |", bits / double(E), 100 * (bits - level_bits[m + 1]) / level_bits[m + 1]);
    }
    std::printf("\n");
  }
  std::printf("all levels:");
  for (size_t vi = 0; vi < kVariants; ++vi) std::printf(" %s %+.1f%%;", variants[vi].name, 100 * (var_all[vi] - all_bits) / all_bits);
  std::printf("\n");
  std::printf("all levels: neighbour context %+.1f%%, prediction %+.1f%%, parent ends %+.1f%%, both %+.1f%%\n",
              100 * (nb_all[0] - all_bits) / all_bits, 100 * (nb_all[1] - all_bits) / all_bits,
              100 * (nb_all[2] - all_bits) / all_bits, 100 * (nb_all[3] - all_bits) / all_bits);
  std::printf("\ntoday, all levels: %.0f bits = %.0f bytes (ideal costing)\n", all_bits, all_bits / 8);
  return 0;
}

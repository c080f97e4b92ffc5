// Garland-Heckbert quadric edge collapse.  Our own rather than OpenMesh's
// decimater: OpenMesh needed ~0.3 s on the bunny's shell (most of the
// control-mesh budget) and stopped two triangles short of the target; this
// one collapses to the exact even target in a few tens of milliseconds.
//
// Open meshes (an edge in one triangle is a boundary, or rim, edge) follow
// Garland and Heckbert's boundary handling: every rim edge adds to its ends'
// quadrics a weighted plane through it, perpendicular to its
// triangle, so collapses along the rim keep its curve; an edge from the rim
// inwards collapses onto its rim end; the link condition counts the one
// triangle of a rim edge.  Nothing of this runs on a closed mesh, whose
// output stays bit for bit what it was.
#include "dbss/encoder/simplify.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <string>

namespace dbss {

namespace {

using Vec3 = Eigen::Vector3d;

// Weight of a rim edge's constraint plane per squared edge length, against
// a face plane's weight of twice its area (about 0.87 per squared edge):
// ten faces' worth, so collapses along the rim keep its curve.  Not the
// thousand often used: a wrapped sheet's rim wiggles by about a point
// spacing, and on a scanned hemisphere 1000 kept twice the rim vertices of
// 10 (239 against 165 of about 1000) for a rim no closer to the true one.
constexpr double kRimWeight = 10;

// Solves A x = r by the adjugate, unless A is singular or so ill
// conditioned (reciprocal condition number in the 1-norm, computed exactly
// from the inverse, under 1e-9) that x would be noise.  Replaces Eigen's
// FullPivLU with its condition estimate, which cost about a third of the
// simplifier's time on the bunny's 74k-triangle shell.
bool solve_3x3(const Eigen::Matrix3d& A, const Vec3& r, Vec3& x) {
  const Vec3 c0 = A.col(1).cross(A.col(2)), c1 = A.col(2).cross(A.col(0)), c2 = A.col(0).cross(A.col(1));
  const double det = A.col(0).dot(c0);
  if (!(std::abs(det) > 0) || !std::isfinite(det)) return false;
  // The inverse's rows are c0, c1, c2 over det.
  const double norm_a = std::max({A.col(0).lpNorm<1>(), A.col(1).lpNorm<1>(), A.col(2).lpNorm<1>()});
  const double norm_inv = std::max({std::abs(c0[0]) + std::abs(c1[0]) + std::abs(c2[0]), std::abs(c0[1]) + std::abs(c1[1]) + std::abs(c2[1]),
                                    std::abs(c0[2]) + std::abs(c1[2]) + std::abs(c2[2])}) /
                          std::abs(det);
  if (!(norm_a * norm_inv < 1e9)) return false;
  x = Vec3(c0.dot(r), c1.dot(r), c2.dot(r)) / det;
  return true;
}

// A symmetric 4x4 quadric as its plane-equation sum.
struct Quadric {
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Vec3 b = Vec3::Zero();
  double c = 0;
  void add_plane(const Vec3& n, double d, double w) {
    A += w * n * n.transpose();
    b += w * d * n;
    c += w * d * d;
  }
  Quadric& operator+=(const Quadric& o) {
    A += o.A, b += o.b, c += o.c;
    return *this;
  }
  double error(const Vec3& p) const { return p.dot(A * p) + 2 * b.dot(p) + c; }
};

// One candidate per edge that may still collapse, kept up to date: a
// collapse gives the candidates at both its ends to the merged vertex with
// their new costs (see collapse()), so the heap never holds a stale entry.  (It used to: every
// push stayed until popped, stale or not, and nine of ten pops on the
// bunny's 73k-triangle shell were stale, each a sift through a heap of some
// 300k entries and a read of a candidate far away in memory.)
constexpr uint32_t kNone = 0xFFFFFFFFu;
struct Candidate {
  uint32_t end[2];  // the edge's vertices, end[0] < end[1]
  // The candidates at each end form a doubly linked list through these
  // (next[k]/prev[k]: the list of end[k]), so a collapse finds and unlinks
  // them without a search.
  uint32_t next[2], prev[2];
  // (Where the collapse puts the vertex is solved for again when the
  // candidate comes off the heap, to the same bits since nothing it depends
  // on has changed: one solve per collapse instead of a 24-byte store per
  // push, ten pushes per collapse on the bunny 35k.)
};
// The heap holds a cost, the push's sequence number and the candidate's
// slot (16 bytes, not the candidate's 24): sifting moves less memory.
struct HeapEntry {
  double cost;
  uint32_t seq;
  uint32_t slot;
};

// Each vertex's triangles, in the order they were added: up to 15 in one
// 64-byte line with their count, more (rare: a vertex that swallowed many)
// in a vector of their own.  A vector per vertex cost a second cache miss
// per list read, and the link and fold checks of every collapse read the
// lists of both ends (collapse_ok was memory bound on them).
class FaceLists {
 public:
  explicit FaceLists(size_t n) : raw_(kLine * n + kLine - 1, 0), big_(n) {
    // The first line boundary in raw_ (vector storage is only 16-aligned).
    const auto addr = reinterpret_cast<uintptr_t>(raw_.data());
    base_ = raw_.data() + ((kLine * sizeof(uint32_t) - addr % (kLine * sizeof(uint32_t))) % (kLine * sizeof(uint32_t))) / sizeof(uint32_t);
  }
  std::span<const uint32_t> operator[](uint32_t v) const {
    const uint32_t* d = line(v);
    return d[0] == kBig ? std::span<const uint32_t>(big_[v]) : std::span<const uint32_t>(d + 1, d[0]);
  }
  void push_back(uint32_t v, uint32_t f) {
    uint32_t* d = line(v);
    if (d[0] < kInline) {
      d[1 + d[0]++] = f;
      return;
    }
    if (d[0] == kInline) {
      big_[v].assign(d + 1, d + 1 + kInline);
      d[0] = kBig;
    }
    big_[v].push_back(f);
  }
  // Takes f out of v's list (where it is at most once), the rest in order.
  void erase(uint32_t v, uint32_t f) {
    uint32_t* d = line(v);
    if (d[0] == kBig) {
      big_[v].erase(std::remove(big_[v].begin(), big_[v].end(), f), big_[v].end());
      return;
    }
    uint32_t* end = std::remove(d + 1, d + 1 + d[0], f);
    d[0] = static_cast<uint32_t>(end - (d + 1));
  }
  void clear(uint32_t v) {
    uint32_t* d = line(v);
    if (d[0] == kBig) big_[v] = {};
    d[0] = 0;
  }

 private:
  static constexpr size_t kLine = 16;  // uint32_t per line: the count and kInline triangles
  static constexpr uint32_t kInline = kLine - 1;
  static constexpr uint32_t kBig = UINT32_MAX;  // count of a list kept in big_
  uint32_t* line(uint32_t v) { return base_ + kLine * v; }
  const uint32_t* line(uint32_t v) const { return base_ + kLine * v; }
  std::vector<uint32_t> raw_;
  uint32_t* base_ = nullptr;
  std::vector<std::vector<uint32_t>> big_;
};

class Simplifier {
 public:
  Simplifier(const TriangleMesh& m, double needle)
      : tris_(m.triangles), alive_(m.triangle_count(), 1), needle_(needle), faces_of_(m.vertex_count()) {
    const size_t n = m.vertex_count();
    pos_.resize(n);
    for (size_t v = 0; v < n; ++v) pos_[v] = Vec3(m.positions[3 * v], m.positions[3 * v + 1], m.positions[3 * v + 2]);
    for (uint32_t f = 0; f < m.triangle_count(); ++f)
      for (int k = 0; k < 3; ++k) faces_of_.push_back(tris_[3 * f + k], f);
    head_.assign(n, kNone);
    slot_at_.assign(n, kNone);
    q_.resize(n);
    for (uint32_t f = 0; f < m.triangle_count(); ++f) {
      const Vec3 n3 = face_cross(f);
      const double area2 = n3.norm();
      if (area2 <= 0) continue;
      const Vec3 nn = n3 / area2;
      const double d = -nn.dot(pos_[tris_[3 * f]]);
      for (int k = 0; k < 3; ++k) q_[tris_[3 * f + k]].add_plane(nn, d, area2);
    }
    add_rim_planes();
    faces_ = m.triangle_count();
    // A closed mesh has 1.5 edges per triangle; reserved so the pool and
    // heap are not copied as they grow.
    pool_.reserve(m.triangle_count() * 3 / 2 + 16);
    heap_.reserve(m.triangle_count() * 3 / 2 + 16);
    for (uint32_t f = 0; f < m.triangle_count(); ++f)
      for (int k = 0; k < 3; ++k) {
        const uint32_t a = tris_[3 * f + k], b = tris_[3 * f + (k + 1) % 3];
        if (a < b) push(a, b);
      }
  }

  void run(uint32_t target) {
    while (faces_ > target && !heap_.empty()) {
      // Every candidate in the heap is current; a refused one leaves it
      // until an edge at one of its ends collapses and pushes it again.
      const uint32_t slot = heap_[0].slot;
      const uint32_t u = pool_[slot].end[0], v = pool_[slot].end[1];
      drop(slot);
      Vec3 p;
      optimal(u, v, p);
      if (!collapse_ok(u, v, p)) continue;
      collapse(u, v, p);
    }
  }

  TriangleMesh result() const {
    TriangleMesh out;
    std::vector<uint32_t> id(pos_.size(), 0xFFFFFFFFu);
    for (uint32_t f = 0; f < alive_.size(); ++f) {
      if (!alive_[f]) continue;
      for (int k = 0; k < 3; ++k) {
        const uint32_t v = tris_[3 * f + k];
        if (id[v] == 0xFFFFFFFFu) {
          id[v] = static_cast<uint32_t>(out.vertex_count());
          for (int a = 0; a < 3; ++a) out.positions.push_back(static_cast<float>(pos_[v][a]));
        }
        out.triangles.push_back(id[v]);
      }
    }
    return out;
  }

  uint32_t faces() const { return faces_; }

 private:
  // Marks the rim vertices and adds each rim edge's constraint plane to its
  // ends' quadrics.  A half-edge without its opposite is a rim edge.
  void add_rim_planes() {
    rim_.assign(pos_.size(), 0);
    // Is b -> a a side of a triangle at b?  Looked up in b's fan (a dozen
    // triangles) rather than by sorting every half-edge of the shell.
    const auto has_twin = [&](uint32_t a, uint32_t b) {
      for (uint32_t g : faces_of_[b])
        for (int k = 0; k < 3; ++k)
          if (tris_[3 * g + k] == b && tris_[3 * g + (k + 1) % 3] == a) return true;
      return false;
    };
    for (uint32_t f = 0; f < alive_.size(); ++f)
      for (int k = 0; k < 3; ++k) {
        const uint32_t a = tris_[3 * f + k], b = tris_[3 * f + (k + 1) % 3];
        if (has_twin(a, b)) continue;
        rim_[a] = rim_[b] = 1;
        const Vec3 edge = pos_[b] - pos_[a];
        const Vec3 n = edge.cross(face_cross(f));
        if (n.norm() <= 0) continue;  // degenerate triangle: no plane to keep
        const Vec3 nn = n.normalized();
        const double w = kRimWeight * edge.squaredNorm();
        q_[a].add_plane(nn, -nn.dot(pos_[a]), w);
        q_[b].add_plane(nn, -nn.dot(pos_[a]), w);
      }
  }

  // Triangles on edge uv: 1 on the rim, 2 inside.
  int edge_faces(uint32_t u, uint32_t v) const {
    int n = 0;
    for (uint32_t f : faces_of_[u])
      for (int k = 0; k < 3; ++k) n += tris_[3 * f + k] == v;
    return n;
  }

  Vec3 face_cross(uint32_t f) const {
    const Vec3& a = pos_[tris_[3 * f]];
    return (pos_[tris_[3 * f + 1]] - a).cross(pos_[tris_[3 * f + 2]] - a);
  }

  // The point minimising the summed quadric, or the best of the ends and the
  // midpoint when the system is singular (flat or straight neighbourhoods).
  double optimal(uint32_t u, uint32_t v, Vec3& best) const {
    Quadric q = q_[u];
    q += q_[v];
    // From the rim inwards: onto the rim end, so the rim stays where it is
    // (a free optimum would pull it into the sheet).
    if (rim_[u] != rim_[v]) {
      best = rim_[u] ? pos_[u] : pos_[v];
      return q.error(best);
    }
    if (solve_3x3(q.A, -q.b, best)) {
      // Keep the point near the edge: a far optimum of an ill-conditioned
      // quadric makes spikes.
      const double len = (pos_[u] - pos_[v]).norm();
      if ((best - 0.5 * (pos_[u] + pos_[v])).norm() <= 2 * len) return q.error(best);
    }
    const Vec3 cand[3] = {pos_[u], pos_[v], 0.5 * (pos_[u] + pos_[v])};
    double e = q.error(cand[0]);
    best = cand[0];
    for (int i = 1; i < 3; ++i)
      if (double x = q.error(cand[i]); x < e) e = x, best = cand[i];
    return e;
  }

  // u < v.
  void push(uint32_t u, uint32_t v) {
    Vec3 p;
    const double e = optimal(u, v, p);
    uint32_t slot;
    if (free_.empty()) {
      slot = static_cast<uint32_t>(pool_.size());
      pool_.emplace_back();
      where_.push_back(0);
    } else {
      slot = free_.back();
      free_.pop_back();
    }
    pool_[slot].end[0] = u, pool_[slot].end[1] = v;
    link(slot, 0);
    link(slot, 1);
    where_[slot] = static_cast<uint32_t>(heap_.size());
    heap_.push_back({std::max(0.0, e), seq_++, slot});
    sift_up(heap_.size() - 1);
  }

  // Which end of candidate `slot` vertex x is.
  int side(uint32_t slot, uint32_t x) const { return pool_[slot].end[0] == x ? 0 : 1; }

  // Takes candidate `slot` out of the heap and its ends' lists, and frees it.
  void drop(uint32_t slot) {
    unlink(slot, 0);
    unlink(slot, 1);
    unheap(slot);
  }
  // Takes candidate `slot` out of the list of its end k.
  void unlink(uint32_t slot, int k) {
    const Candidate& c = pool_[slot];
    const uint32_t x = c.end[k], n = c.next[k], pr = c.prev[k];
    if (pr != kNone) pool_[pr].next[side(pr, x)] = n;
    else head_[x] = n;
    if (n != kNone) pool_[n].prev[side(n, x)] = pr;
  }
  // Puts candidate `slot` first in the list of its end k.
  void link(uint32_t slot, int k) {
    Candidate& c = pool_[slot];
    const uint32_t x = c.end[k], h = head_[x];
    c.next[k] = h, c.prev[k] = kNone;
    if (h != kNone) pool_[h].prev[side(h, x)] = slot;
    head_[x] = slot;
  }
  // Takes candidate `slot` out of the heap and frees it (its lists are the
  // caller's business).
  void unheap(uint32_t slot) {
    const size_t i = where_[slot];
    const HeapEntry last = heap_.back();
    heap_.pop_back();
    if (i < heap_.size()) {
      heap_[i] = last;
      where_[last.slot] = static_cast<uint32_t>(i);
      sift_up(i);
      sift_down(where_[last.slot]);
    }
    free_.push_back(slot);
  }

  // The heap's order: by cost, ties first pushed first, so which collapse
  // comes first never depends on the heap's layout.  Ties are common: a
  // flat region's collapses all cost 0.  Taking them by the edge's ends
  // instead let the lowest-numbered vertex swallow a flat disc whole; in
  // push order they spread over it as the old heap's arbitrary order did.
  // (The sequence number wraps after 2^32 pushes, a mesh of some 500M
  // triangles; the order stays a valid one.)
  static bool before(const HeapEntry& a, const HeapEntry& b) {
    if (a.cost != b.cost) return a.cost < b.cost;
    return a.seq < b.seq;
  }
  void place(size_t i, const HeapEntry& e) {
    heap_[i] = e;
    where_[e.slot] = static_cast<uint32_t>(i);
  }
  // A 4-ary heap: half the levels of a binary one, and a node's children
  // side by side (64 bytes), so a sift misses the cache about half as often;
  // a collapse updates some ten candidates in place.  Its order is a total
  // one (the sequence numbers differ), so the pops are the same as a binary
  // heap's.
  static constexpr size_t kArity = 4;
  void sift_up(size_t i) {
    const HeapEntry e = heap_[i];
    while (i > 0) {
      const size_t parent = (i - 1) / kArity;
      if (!before(e, heap_[parent])) break;
      place(i, heap_[parent]);
      i = parent;
    }
    place(i, e);
  }
  void sift_down(size_t i) {
    const HeapEntry e = heap_[i];
    const size_t n = heap_.size();
    for (;;) {
      const size_t first = kArity * i + 1;
      if (first >= n) break;
      size_t child = first;
      for (size_t c = first + 1; c < std::min(n, first + kArity); ++c)
        if (before(heap_[c], heap_[child])) child = c;
      if (!before(heap_[child], e)) break;
      place(i, heap_[child]);
      i = child;
    }
    place(i, e);
  }

  // A fresh run of `span` mark values, every mark below the first of them.
  uint32_t next_mark(uint32_t span) {
    if (mark_.empty()) mark_.assign(pos_.size(), 0);
    if (mark_top_ > UINT32_MAX - span - 1) mark_.assign(pos_.size(), 0), mark_top_ = 0;
    const uint32_t first = mark_top_ + 1;
    mark_top_ += span;
    return first;
  }

  size_t distinct_neighbours(uint32_t v) {
    const uint32_t m = next_mark(1);
    size_t count = 0;
    for (uint32_t f : faces_of_[v])
      for (int k = 0; k < 3; ++k)
        if (const uint32_t w = tris_[3 * f + k]; w != v && mark_[w] != m) mark_[w] = m, ++count;
    return count;
  }

  void neighbours(uint32_t v, std::vector<uint32_t>& out) const {
    out.clear();
    for (uint32_t f : faces_of_[v])
      for (int k = 0; k < 3; ++k)
        if (uint32_t w = tris_[3 * f + k]; w != v) out.push_back(w);
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
  }

  bool collapse_ok(uint32_t u, uint32_t v, const Vec3& p) {
    // Link condition: the edge's ends share exactly its opposite vertices
    // (two, or one on a rim edge); anything more would pinch off a handle or
    // a component, changing the topology.  An inner edge between two rim
    // vertices would pinch the sheet at the merged vertex (or join two rim
    // loops), so it stays.
    const bool rim_edge = rim_[u] && rim_[v] && edge_faces(u, v) == 1;
    if (rim_[u] && rim_[v] && !rim_edge) return false;
    // Only how many neighbours u and v have, and which they share, matter
    // here: counted with marks rather than sorted lists (sorting them was a
    // tenth of the simplifier's time).
    const uint32_t mark_u = next_mark(3);
    size_t count_u = 0, count_v = 0;
    for (uint32_t f : faces_of_[u])
      for (int k = 0; k < 3; ++k)
        if (const uint32_t w = tris_[3 * f + k]; w != u && mark_[w] < mark_u) mark_[w] = mark_u, ++count_u;
    // v's neighbours: mark_u + 1 when u's as well, mark_u + 2 when not.
    common_.clear();
    for (uint32_t f : faces_of_[v])
      for (int k = 0; k < 3; ++k) {
        const uint32_t w = tris_[3 * f + k];
        if (w == v || mark_[w] > mark_u) continue;
        ++count_v;
        if (mark_[w] == mark_u) {
          mark_[w] = mark_u + 1;
          common_.push_back(w);
        } else {
          mark_[w] = mark_u + 2;
        }
      }
    if (common_.size() != (rim_edge ? 1u : 2u)) return false;
    // Valences stay at least 3 (no tetrahedron collapses into a sheet, no
    // rim vertex is left with a single triangle).
    if (count_u + count_v - 2 - common_.size() < 3) return false;
    for (uint32_t w : common_)
      if (distinct_neighbours(w) < 4) return false;
    // Moved triangles must not turn over (more than 60 degrees) or become needles.
    for (uint32_t x : {u, v})
      for (uint32_t f : faces_of_[x]) {
        bool has_u = false, has_v = false;
        Vec3 c[3];
        for (int k = 0; k < 3; ++k) {
          const uint32_t w = tris_[3 * f + k];
          has_u |= w == u, has_v |= w == v;
          c[k] = (w == u || w == v) ? p : pos_[w];
        }
        if (has_u && has_v) continue;  // removed by the collapse
        const Vec3 before = face_cross(f);
        const Vec3 after = (c[1] - c[0]).cross(c[2] - c[0]);
        const double la = after.norm(), lb = before.norm();
        if (la <= 0 || lb <= 0 || after.dot(before) < 0.5 * la * lb) return false;
        // Needles: twice the area under needle_ times the longest side
        // squared (see SimplifyOptions::needle).
        const double longest = std::max({(c[1] - c[0]).squaredNorm(), (c[2] - c[1]).squaredNorm(), (c[0] - c[2]).squaredNorm()});
        if (la < needle_ * longest) return false;
      }
    return true;
  }

  void collapse(uint32_t u, uint32_t v, const Vec3& p) {
    // Every candidate at u or v is out of date (their quadrics and places
    // change, and v goes).  They are taken off u's and v's lists here and
    // below become u's candidates again, updated in place: the same costs
    // and push order as dropping them and pushing anew (so the same
    // collapses), without freeing, relinking at their other end and
    // re-inserting each one.
    mine_.clear();
    for (uint32_t x : {u, v}) {
      for (uint32_t slot = head_[x]; slot != kNone;) {
        const uint32_t next = pool_[slot].next[side(slot, x)];
        // A second candidate for edge uv (triangles that disagree on its
        // direction) is in both lists: taken once.
        if (x == u || pool_[slot].end[0] != u) mine_.push_back(slot);
        slot = next;
      }
      head_[x] = kNone;
    }
    for (uint32_t f : faces_of_[v]) {
      bool has_u = false;
      for (int k = 0; k < 3; ++k) has_u |= tris_[3 * f + k] == u;
      if (has_u) {
        alive_[f] = 0;
        --faces_;
        for (int k = 0; k < 3; ++k)
          if (tris_[3 * f + k] != v) faces_of_.erase(tris_[3 * f + k], f);
      } else {
        for (int k = 0; k < 3; ++k)
          if (tris_[3 * f + k] == v) tris_[3 * f + k] = u;
        faces_of_.push_back(u, f);
      }
    }
    faces_of_.clear(v);
    rim_[u] |= rim_[v];
    pos_[u] = p;
    q_[u] += q_[v];
    // One candidate per edge at u, each still linked at its other end w.
    for (uint32_t slot : mine_) {
      Candidate& c = pool_[slot];
      int k = c.end[0] == u || c.end[0] == v ? 0 : 1;  // the end at u or v
      const uint32_t w = c.end[1 - k];
      if (w == u || w == v) {  // uv itself, a second time
        unheap(slot);
        continue;
      }
      if (slot_at_[w] != kNone) {  // u and v's common neighbour, a second time
        unlink(slot, 1 - k);
        unheap(slot);
        continue;
      }
      slot_at_[w] = slot;
      c.end[k] = u;
      if (c.end[0] > c.end[1]) {  // ends in order again, links with them
        std::swap(c.end[0], c.end[1]);
        std::swap(c.next[0], c.next[1]);
        std::swap(c.prev[0], c.prev[1]);
        k = 1 - k;
      }
      link(slot, k);
    }
    // Only edges at u change cost (their quadric and end moved); validity
    // elsewhere is checked when an edge comes off the heap.  In the order
    // of w, each a fresh push: new cost, next sequence number.
    neighbours(u, nu_);
    for (uint32_t w : nu_) {
      const uint32_t slot = slot_at_[w];
      if (slot == kNone) {  // refused before, or never pushed
        push(std::min(u, w), std::max(u, w));
        continue;
      }
      slot_at_[w] = kNone;
      Vec3 p_unused;
      const double e = optimal(pool_[slot].end[0], pool_[slot].end[1], p_unused);
      const size_t i = where_[slot];
      heap_[i] = {std::max(0.0, e), seq_++, slot};
      sift_up(i);
      sift_down(where_[slot]);
    }
    // (No edge at u leads elsewhere: its neighbours are u's and v's.)
    for (uint32_t slot : mine_)
      for (int k = 0; k < 2; ++k)
        if (const uint32_t w = pool_[slot].end[k]; w != u && slot_at_[w] == slot) {
          slot_at_[w] = kNone;
          drop(slot);
        }
  }

  std::vector<uint32_t> tris_;
  std::vector<uint8_t> alive_;
  double needle_;  // SimplifyOptions::needle
  std::vector<Vec3> pos_;
  FaceLists faces_of_;
  std::vector<uint8_t> rim_;  // on an edge with one triangle
  std::vector<Quadric> q_;
  uint32_t faces_ = 0;
  std::vector<HeapEntry> heap_;  // a 4-ary min-heap in the order of before()
  std::vector<Candidate> pool_;  // the candidates, by HeapEntry::slot
  std::vector<uint32_t> where_;  // per slot, its index in heap_
  std::vector<uint32_t> free_;   // slots of candidates dropped
  uint32_t seq_ = 0;             // pushes so far
  std::vector<uint32_t> head_;   // per vertex, the first candidate at it (kNone: none)
  std::vector<uint32_t> mine_;     // collapse(): the candidates at u and v
  std::vector<uint32_t> slot_at_;  // collapse(): per neighbour of u, its candidate (kNone: none)
  std::vector<uint32_t> nu_, common_;
  std::vector<uint32_t> mark_;  // per vertex, see next_mark()
  uint32_t mark_top_ = 0;
};

}  // namespace

uint32_t default_control_faces(uint32_t shell_faces, int64_t genus) {
  const int64_t lo = 96 + 64 * std::max<int64_t>(0, genus);
  const int64_t f = std::clamp<int64_t>(shell_faces / 24, lo, std::max<int64_t>(lo, 4000));
  return static_cast<uint32_t>(f & ~int64_t{1});
}

Result<TriangleMesh> simplify_mesh(const TriangleMesh& in, uint32_t target_faces, SimplifyStats* stats,
                                   const SimplifyOptions& options) {
  if (in.triangle_count() == 0) return Status(ErrorCode::invalid_argument, "simplify: empty mesh");
  Simplifier s(in, options.needle);
  s.run(target_faces);
  TriangleMesh out = s.result();
  if (stats) {
    stats->faces_before = static_cast<uint32_t>(in.triangle_count());
    stats->faces_after = static_cast<uint32_t>(out.triangle_count());
  }
  return out;
}

}  // namespace dbss

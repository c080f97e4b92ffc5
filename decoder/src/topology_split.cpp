// Topology split: one level's connectivity from the level below (no geometry).
// Child connectivity from the parent's regular 1-to-4 split, without any
// search: every child entry is a function of a few parent entries, so the
// work splits over contiguous face ranges (spec/decoding.md section 4).
#include "topology_ref.h"

namespace dbss {
namespace detail {

namespace {

// Child half-edges of parent face f are 12f + s, s = 0..11 ("slots"):
//   slot 3k+0: child k, v_k -> m_k,        first half of parent 3f+k
//   slot 3k+1: child k, m_k -> m_{k+2},    inside f, twin of slot 9+(k+2)%3
//   slot 3k+2: child k, m_{k+2} -> v_k,    second half of parent 3f+(k+2)%3
//   slot 9+j:  centre,  m_j -> m_{j+1},    inside f, twin of slot 3((j+1)%3)+1
// Slots 3k+1 always open an edge and slots 9..11 never do; a split half
// opens one exactly when its parent half-edge does (its twin lies in the
// twin's face, later or earlier like the parent's).  `open` has bit k set
// when parent half-edge 3f+k opens an edge.
constexpr bool slot_opens(uint32_t open, uint32_t s) {
  return s % 3 == 1 || (open >> (s % 3 == 0 ? s / 3 : (s / 3 + 2) % 3) & 1);
}

// kRank[open][s]: how many of slots 0..s-1 open an edge.
struct RankTable {
  uint8_t r[8][10];
  constexpr RankTable() : r{} {
    for (uint32_t open = 0; open < 8; ++open)
      for (uint32_t s = 0; s < 9; ++s) r[open][s + 1] = static_cast<uint8_t>(r[open][s] + (slot_opens(open, s) ? 1 : 0));
  }
};
constexpr RankTable kRank;

inline uint32_t open_bits(const uint32_t* twin, uint32_t f) {
  const uint32_t h = 3 * f;
  return (opens_edge(twin, h) ? 1u : 0u) | (opens_edge(twin, h + 1) ? 2u : 0u) | (opens_edge(twin, h + 2) ? 4u : 0u);
}

// The child edges of face f are numbered from 3f + 2P, P = parent edges
// opened before f: each earlier face opened its 3 inner edges and 2 per
// parent edge it opened.
inline uint32_t child_edge_base(uint32_t f, uint32_t parent_edges_before) { return 3 * f + 2 * parent_edges_before; }

}  // namespace

void refine_triangle_range(const TopologyRef& p, uint32_t fb, uint32_t fe, uint32_t* out) {
  const uint32_t base = p.vertex_count;
  const uint32_t* tri = p.tri + 3 * size_t{fb};
  const uint32_t* eo = p.edge_of + 3 * size_t{fb};
  uint32_t* o = out + 12 * size_t{fb};
  for (uint32_t f = fb; f < fe; ++f, tri += 3, eo += 3, o += 12) {
    const uint32_t m0 = base + eo[0], m1 = base + eo[1], m2 = base + eo[2];
    o[0] = tri[0], o[1] = m0, o[2] = m2;
    o[3] = tri[1], o[4] = m1, o[5] = m0;
    o[6] = tri[2], o[7] = m2, o[8] = m1;
    o[9] = m0, o[10] = m1, o[11] = m2;
  }
}

void refine_faces(const TopologyRef& p, uint32_t fb, uint32_t fe, const TopologyOut& c) {
  if (c.tri) refine_triangle_range(p, fb, fe, c.tri);
  uint32_t pe = first_edge_of_face(p, fb);  // parent edges opened before f
  for (uint32_t f = fb; f < fe; ++f) {
    if (f + 8 < fe)  // the neighbours' tables are the far-away reads: ask early (a hint only)
      for (uint32_t k = 0; k < 3; ++k) {
        const uint32_t g = p.twin[3 * (f + 8) + k];
        if (g != kNoHalfEdge) __builtin_prefetch(p.twin + 3 * (g / 3)), __builtin_prefetch(p.edge_of + 3 * (g / 3));
      }
    const uint32_t cf = 12 * f;
    const uint32_t* ptw = p.twin + 3 * size_t{f};
    const uint32_t open = open_bits(p.twin, f);
    // Twins (the table in the comment above).
    for (uint32_t k = 0; k < 3; ++k) {
      const uint32_t ph = ptw[k], pp = ptw[(k + 2) % 3];
      c.twin[cf + 3 * k + 0] = ph == kNoHalfEdge ? kNoHalfEdge : 12 * (ph / 3) + 3 * ((ph % 3 + 1) % 3) + 2;
      c.twin[cf + 3 * k + 1] = cf + 9 + (k + 2) % 3;
      c.twin[cf + 3 * k + 2] = pp == kNoHalfEdge ? kNoHalfEdge : 12 * (pp / 3) + 3 * (pp % 3) + 0;
      c.twin[cf + 9 + k] = cf + 3 * ((k + 1) % 3) + 1;
    }
    // Edge numbers: opening slots count up from the face's base (kRank); the
    // two halves of a parent edge that f does not open take the edges of
    // their twins' slots in the earlier face g, found from g's own base and
    // open bits.
    const uint32_t base = child_edge_base(f, pe);
    const uint8_t* rank = kRank.r[open];
    const auto number = [&](uint32_t s, uint32_t e) {
      c.edge_of[cf + s] = e;
      if (c.edge_half) c.edge_half[e] = cf + s;
    };
    // Crease flags: both halves of a crease edge are creases, the edges
    // inside f never are; each child edge is written by the face that
    // opens it.
    const bool creases = p.crease && c.crease;
    for (uint32_t k = 0; k < 3; ++k) {
      const uint32_t first = 3 * k, second = 3 * ((k + 1) % 3) + 2;  // the halves of parent 3f+k
      number(3 * k + 1, base + rank[3 * k + 1]);                       // inner edge m_k -> m_{k+2}
      if (creases) c.crease[base + rank[3 * k + 1]] = 0;
      if (open >> k & 1) {
        number(first, base + rank[first]);
        number(second, base + rank[second]);
        if (creases) c.crease[base + rank[first]] = c.crease[base + rank[second]] = p.crease[p.edge_of[3 * f + k]];
        continue;
      }
      const uint32_t g = ptw[k], gf = g / 3, j = g % 3;
      const uint32_t gopen = open_bits(p.twin, gf);
      constexpr uint8_t kBits[8] = {0, 1, 1, 2, 1, 2, 2, 3};  // popcount of 3 bits (no popcnt on baseline x86-64)
      // p.edge_of[3f+k] is also g's edge: g's face opened that many edges,
      // minus those g's earlier half-edges opened, before g's block.
      const uint32_t gbase = child_edge_base(gf, p.edge_of[3 * f + k] - kBits[gopen & ((1u << j) - 1)]);
      c.edge_of[cf + first] = gbase + kRank.r[gopen][3 * ((j + 1) % 3) + 2];  // g's second half
      c.edge_of[cf + second] = gbase + kRank.r[gopen][3 * j];                 // g's first half
    }
    for (uint32_t j = 0; j < 3; ++j) c.edge_of[cf + 9 + j] = c.edge_of[cf + 3 * ((j + 1) % 3) + 1];
    if (c.across) {
      // The vertex across each child half-edge: inside f a corner or odd
      // vertex of f; across a split half, the odd vertex of the neighbour's
      // half-edge that the neighbour's child triangle ends at.
      const uint32_t* eo = p.edge_of + 3 * size_t{f};
      const uint32_t* tri = p.tri + 3 * size_t{f};
      const auto odd_of = [&](uint32_t g, uint32_t step) {
        return p.vertex_count + p.edge_of[3 * (g / 3) + (g % 3 + step) % 3];
      };
      for (uint32_t k = 0; k < 3; ++k) {
        const uint32_t ph = ptw[k], pp = ptw[(k + 2) % 3];
        c.across[cf + 3 * k + 0] = ph == kNoHalfEdge ? kNoHalfEdge : odd_of(ph, 1);
        c.across[cf + 3 * k + 1] = p.vertex_count + eo[(k + 1) % 3];
        c.across[cf + 3 * k + 2] = pp == kNoHalfEdge ? kNoHalfEdge : odd_of(pp, 2);
        c.across[cf + 9 + k] = tri[(k + 1) % 3];
      }
    }
    // Odd vertices of the parent edges f opens: valence 6, or 4 on a
    // boundary edge where the fan starts at the outgoing boundary half
    // m_k -> v_{k+1} (child k+1, slot 2).
    for (uint32_t k = 0; k < 3; ++k) {
      if (!(open >> k & 1)) continue;
      const uint32_t v = p.vertex_count + pe++;
      if (ptw[k] == kNoHalfEdge) {
        c.vertex_start[v] = cf + 3 * ((k + 1) % 3) + 2;
        c.valence[v] = 4;
        c.boundary[v] = 1;
      } else {
        c.vertex_start[v] = cf + 3 * k + 1;
        c.valence[v] = 6;
        // On a crease edge: a sharp vertex with two crease edges, never an end.
        c.boundary[v] = p.crease && p.crease[v - p.vertex_count] ? kVertexSharp : 0;
      }
    }
  }
}

void refine_vertices(const TopologyRef& p, uint32_t vb, uint32_t ve, const TopologyOut& c) {
  // Even vertices keep valence and kind (boundary, sharp, crease end: the
  // crease edges at a vertex keep their number); their fan starts at the
  // first half of the parent's start half-edge.
  for (uint32_t v = vb; v < ve; ++v) {
    const uint32_t h = p.vertex_start[v];
    c.vertex_start[v] = 12 * (h / 3) + 3 * (h % 3);
    c.valence[v] = p.valence[v];
    c.boundary[v] = p.boundary[v];
  }
}

}  // namespace detail

void refine_triangles(const LevelTopology& parent, std::vector<uint32_t>& out) {
  const detail::TopologyRef p = detail::ref_of(parent);
  out.resize(size_t{p.face_count} * 12);
  detail::refine_triangle_range(p, 0, p.face_count, out.data());
}

LevelTopology refine_topology(const LevelTopology& parent) {
  const detail::TopologyRef p = detail::ref_of(parent);
  LevelTopology c;
  c.vertex_count = p.vertex_count + p.edge_count;
  const size_t halves = size_t{p.face_count} * 12;
  c.triangles.resize(halves);
  c.twin.resize(halves);
  c.edge_of.resize(halves);
  c.edge_half.resize(2 * size_t{p.edge_count} + 3 * size_t{p.face_count});
  c.vertex_start.resize(c.vertex_count);
  c.vertex_valence.resize(c.vertex_count);
  c.vertex_boundary.resize(c.vertex_count);
  if (p.crease) c.edge_crease.resize(c.edge_half.size());
  detail::TopologyOut out{c.triangles.data(),    c.twin.data(),           c.edge_of.data(),
                          c.edge_half.data(),    c.vertex_start.data(),   c.vertex_valence.data(),
                          c.vertex_boundary.data()};
  if (p.crease) out.crease = c.edge_crease.data();
  detail::refine_faces(p, 0, p.face_count, out);
  detail::refine_vertices(p, 0, p.vertex_count, out);
  return c;
}

}  // namespace dbss

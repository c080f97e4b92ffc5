// Point clouds sampled from shapes of known genus, given by signed distance
// functions, or from a mesh's surface; built in the tests, no data files
// needed.  And the options the crease tests encode such clouds with.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>
#include <vector>

#include "dbss/decoder/mesh.h"
#include "dbss/encoder/encode.h"
#include "dbss/encoder/point_input.h"
#include "dbss/measure/surface_samples.h"

namespace dbss::test {

using Sdf = std::function<double(double, double, double)>;

// `n` points on a mesh's surface, area-uniform (sample_surface, `seed`):
// a shape with sharp edges sampled as crease_bench samples it.
inline PointCloud sampled(const TriangleMesh& m, size_t n, uint32_t seed) {
  const std::vector<double> p = sample_surface(m, n, seed);
  PointCloud pc;
  pc.xyz.assign(p.begin(), p.end());
  return pc;
}

// The crease tests' options: `levels` levels on two threads, creases
// detected at `angle` degrees (0: off), every other option the library's.
inline EncodeOptions crease_options(double angle, uint32_t levels) {
  EncodeOptions o;
  o.levels = levels;
  o.threads = 2;
  o.creases.angle_degrees = angle;
  return o;
}

// The roof z = s |x| (bending by 2 atan(s) at x = 0), 10k area-uniform
// points on [-1, 1]^2 (spacing about 0.02), no noise, seed 5.
inline PointCloud roof_cloud(double s) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  PointCloud pc;
  for (int i = 0; i < 10000; ++i) {
    const double x = u(rng), y = u(rng);
    pc.xyz.insert(pc.xyz.end(), {float(x), float(y), float(s * std::abs(x))});
  }
  return pc;
}

// n points on the unit sphere with Gaussian noise of `sigma` along the radius.
inline PointCloud noisy_sphere(size_t n, double sigma, uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g(0, 1);
  PointCloud pc;
  for (size_t i = 0; i < n; ++i) {
    const double x = g(rng), y = g(rng), z = g(rng);
    const double s = (1 + sigma * g(rng)) / std::sqrt(x * x + y * y + z * z);
    pc.xyz.insert(pc.xyz.end(), {float(x * s), float(y * s), float(z * s)});
  }
  return pc;
}

inline double torus_sdf(double x, double y, double z, double cx, double cy, double R, double r) {
  const double q = std::hypot(x - cx, y - cy) - R;
  return std::hypot(q, z) - r;
}
inline double sphere_sdf(double x, double y, double z, double cx, double cy, double cz, double r) {
  return std::sqrt((x - cx) * (x - cx) + (y - cy) * (y - cy) + (z - cz) * (z - cz)) - r;
}
inline double box_sdf(double x, double y, double z, double cx, double cy, double cz, double hx, double hy, double hz) {
  const double qx = std::abs(x - cx) - hx, qy = std::abs(y - cy) - hy, qz = std::abs(z - cz) - hz;
  const double ox = std::max(qx, 0.0), oy = std::max(qy, 0.0), oz = std::max(qz, 0.0);
  return std::sqrt(ox * ox + oy * oy + oz * oz) + std::min(std::max({qx, qy, qz}), 0.0);
}

// `count` points on the zero set of `sdf` inside [lo, hi]^3: random starts
// projected by Newton steps along the numerical gradient.
inline PointCloud sample_sdf(const Sdf& sdf, double lo, double hi, size_t count, uint32_t seed = 7) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(lo, hi);
  PointCloud pc;
  const double h = 1e-5 * (hi - lo), tol = 1e-6 * (hi - lo);
  size_t attempts = 0;
  while (pc.size() < count && attempts++ < count * 50) {
    double p[3] = {u(rng), u(rng), u(rng)};
    for (int it = 0; it < 30; ++it) {
      const double d = sdf(p[0], p[1], p[2]);
      if (std::abs(d) < tol) break;
      double g[3];
      for (int a = 0; a < 3; ++a) {
        double q[3] = {p[0], p[1], p[2]};
        q[a] += h;
        g[a] = (sdf(q[0], q[1], q[2]) - d) / h;
      }
      const double gg = g[0] * g[0] + g[1] * g[1] + g[2] * g[2];
      if (gg < 1e-12) break;
      for (int a = 0; a < 3; ++a) p[a] -= d * g[a] / gg;
    }
    if (std::abs(sdf(p[0], p[1], p[2])) < 10 * tol)
      for (double v : p) pc.xyz.push_back(static_cast<float>(v));
  }
  return pc;
}

struct Shape {
  const char* name;
  Sdf sdf;
  double lo, hi;
  uint32_t components;
  int64_t genus;
};

inline std::vector<Shape> genus_shapes() {
  using namespace std::placeholders;
  return {
      {"sphere", [](double x, double y, double z) { return sphere_sdf(x, y, z, 0, 0, 0, 1); }, -1.2, 1.2, 1, 0},
      {"torus", [](double x, double y, double z) { return torus_sdf(x, y, z, 0, 0, 1, 0.35); }, -1.5, 1.5, 1, 1},
      {"double torus",
       [](double x, double y, double z) {
         return std::min(torus_sdf(x, y, z, -0.8, 0, 1, 0.3), torus_sdf(x, y, z, 0.8, 0, 1, 0.3));
       },
       -2.2, 2.2, 1, 2},
      {"triple torus",
       [](double x, double y, double z) {
         return std::min({torus_sdf(x, y, z, -1.6, 0, 1, 0.3), torus_sdf(x, y, z, 0, 0, 1, 0.3),
                          torus_sdf(x, y, z, 1.6, 0, 1, 0.3)});
       },
       -3, 3, 1, 3},
      {"cup (U shape)",
       [](double x, double y, double z) {
         return std::min({box_sdf(x, y, z, -0.8, 0, 0.2, 0.2, 0.5, 0.8), box_sdf(x, y, z, 0.8, 0, 0.2, 0.2, 0.5, 0.8),
                          box_sdf(x, y, z, 0, 0, -0.8, 1.0, 0.5, 0.2)});
       },
       -1.2, 1.2, 1, 0},
      {"two spheres",
       [](double x, double y, double z) {
         return std::min(sphere_sdf(x, y, z, -1.2, 0, 0, 0.7), sphere_sdf(x, y, z, 1.2, 0, 0, 0.7));
       },
       -2.1, 2.1, 2, 0},
      {"thin plate", [](double x, double y, double z) { return box_sdf(x, y, z, 0, 0, 0, 1, 0.7, 0.04); }, -1.1, 1.1, 1, 0},
  };
}

}  // namespace dbss::test

// The encoder's input: points read by the io library (dbss/io), checked for
// what reconstruction needs.
#pragma once

#include <cstddef>
#include <string>

#include "dbss/format/status.h"
#include "dbss/io/geometry_files.h"

namespace dbss {

// Fewest points a surface is reconstructed from.  The smallest control
// mesh has about 50 vertices; from fewer points than that the carving
// breaks the surface apart and the levels clamp most displacements (8
// corners of a cube: 8 components, a third clamped; 40 points on a sphere:
// 93% clamped; 60: 1.4%).
inline constexpr size_t kMinReconstructPoints = 50;

// Checks a cloud is usable for reconstruction: at least
// kMinReconstructPoints finite points, not all on one plane.  The message
// names `name`.
Status check_reconstructible(const PointCloud& cloud, const std::string& name);

}  // namespace dbss

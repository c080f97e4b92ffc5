// The encoder's input: points read by the io library (dbss/io), checked for
// what reconstruction needs.
#pragma once

#include <string>

#include "dbss/format/status.h"
#include "dbss/io/geometry_files.h"

namespace dbss {

// Checks a cloud is usable for reconstruction: at least 4 points not all on
// one plane.  The message names `name`.
Status check_reconstructible(const PointCloud& cloud, const std::string& name);

}  // namespace dbss

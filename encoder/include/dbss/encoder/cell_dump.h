// The carving stage's cells as a mesh, for inspection (encode --dump-stages).
#pragma once

#include <string>

#include "dbss/encoder/cell_carving.h"
#include "dbss/format/status.h"

namespace dbss {

// The outer faces of a set of cells as an OBJ quad mesh, written atomically:
// the occupied cells only, or every solid cell after carving.
Status write_cells_obj(const std::string& path, const CellGrid& grid, bool occupied_only);

}  // namespace dbss

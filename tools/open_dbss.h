// Reading a whole .dbss file for the commands that turn levels into meshes
// (`dbss decode`, `dbss export`).
#pragma once

#include <string>

#include "dbss/decoder/progressive.h"

namespace dbss::tools {

// Reads `input` and feeds all of it to `d`.  False, with the message
// printed under `command`'s name, when the file cannot be read or holds no
// usable control mesh.  Otherwise `end` is the decoder's final status: a
// cut or damaged file keeps the levels verified before the problem (spec
// section 11), and the caller says what it does with them.
bool open_dbss(const char* command, const std::string& input, ProgressiveDecoder& d, Status& end);

}  // namespace dbss::tools

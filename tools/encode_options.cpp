#include "encode_options.h"

#include <charconv>
#include <cstdlib>

namespace dbss::tools {

const char* const kEncodeOptionsHelp =
    "  --grid N               cells along the longest side for cell carving,\n"
    "                         2..1024 (default: the finest grid the point\n"
    "                         spacing keeps closed)\n"
    "  --grid-shift S         with --grid: move the cells by S of a cell along\n"
    "                         each axis, 0 <= S < 1 (default 0; meta's\n"
    "                         encoder.params says grid-shift=0.5 where the grid\n"
    "                         search moved its choice by half a cell)\n"
    "  --control-faces F      triangles of the control mesh, even, >= 4\n"
    "                         (default: a 24th of the carved shell's, or of\n"
    "                         twice an open sheet's; at least 96 + 64 per\n"
    "                         handle, at most 4000; or a quarter of that when\n"
    "                         its bytes-against-error curve is better, up to\n"
    "                         2^18 points: meta control.choice says which;\n"
    "                         mesh input: the budget per hole, or 1.5x it\n"
    "                         when the last level is floor-bound and that is\n"
    "                         cheaper at equal error, also in control.choice)\n"
    "  --control-bits B       Draco position bits of the control mesh, 8..30\n"
    "                         (default: from level 0's distance to the points, never\n"
    "                         finer than the step's; on a clean cloud up to two\n"
    "                         fewer if no level gets over 2% worse; control.choice)\n"
    "  --levels L             subdivision levels with displacements, 0..8, or\n"
    "                         auto (the default): up to the first level with\n"
    "                         more vertices than there are points\n"
    "  --error E              largest quantization error of a displacement,\n"
    "                         relative to the bounding-box diagonal, 1e-7..0.1\n"
    "                         (default 1e-4: the step is 2E x diagonal)\n"
    "  --step S               quantization step in model units, instead of\n"
    "                         --error (every level)\n"
    "  --effort N             zstd level for the displacements, 1..22 (default 19)\n"
    "  --surface MODE         closed, open or auto (default auto): closed bridges\n"
    "                         holes in the scan, open keeps a boundary where the\n"
    "                         points end; auto picks one and says why\n"
    "  --keep-outliers        keep every point (default: isolated points and\n"
    "                         clusters under 2% of the points are dropped)\n"
    "  --crease-angle DEG     tag control edges as creases where the points'\n"
    "                         planes on either side meet at more than DEG\n"
    "                         degrees and one smooth sheet cannot follow them,\n"
    "                         1..179, or off (default 30; point input only):\n"
    "                         the sharp edges of machined parts stay sharp;\n"
    "                         tags make a version 1.1 file, and a surface with\n"
    "                         none found gets the file creases off writes\n"
    "  --no-creases           no crease tags: --crease-angle off\n";
static_assert(format::kMaxLevelsInPractice == 8, "--levels' help above says 0..8");


void set_command_defaults(EncodeOptions& o) {
  o.levels = kAutoLevels;
  o.creases.angle_degrees = kCommandCreaseAngle;
}

OptionParse parse_encode_option(const std::vector<std::string_view>& args, size_t& i, EncodeOptions& o,
                                std::string& error) {
  const std::string_view a = args[i];
  if (a == "--keep-outliers") {
    o.outliers.enabled = false;
    return OptionParse::ok;
  }
  if (a == "--no-creases") {
    o.creases.angle_degrees = 0;
    return OptionParse::ok;
  }
  const bool known = a == "--grid" || a == "--grid-shift" || a == "--control-faces" || a == "--control-bits" || a == "--levels" ||
                     a == "--error" || a == "--step" || a == "--effort" || a == "--surface" || a == "--crease-angle";
  if (!known) return OptionParse::not_mine;
  std::string_view v;
  if (i + 1 < args.size()) v = args[++i];
  else {
    error = std::string(a) + " needs a value";
    return OptionParse::bad;
  }
  long n = 0;
  double x = 0;
  if (a == "--grid") {
    if (!parse_int(v, 2, 1024, n)) return error = "--grid needs a whole number from 2 to 1024", OptionParse::bad;
    o.control.grid = static_cast<int>(n);
  } else if (a == "--grid-shift") {
    if (!parse_double(v, x) || !(x >= 0 && x < 1)) return error = "--grid-shift needs a number from 0 to under 1", OptionParse::bad;
    o.control.grid_shift = x;
  } else if (a == "--control-faces") {
    if (!parse_int(v, 4, 1 << 24, n) || n % 2) return error = "--control-faces needs an even whole number of at least 4", OptionParse::bad;
    o.control.control_faces = static_cast<uint32_t>(n);
  } else if (a == "--control-bits") {
    if (!parse_int(v, 8, 30, n)) return error = "--control-bits needs a whole number from 8 to 30", OptionParse::bad;
    o.control_bits = static_cast<int>(n);
  } else if (a == "--levels") {
    if (v == "auto") {
      o.levels = kAutoLevels;
    } else {
      if (!parse_int(v, 0, format::kMaxLevelsInPractice, n))
        return error = "--levels needs auto or a whole number from 0 to " + std::to_string(format::kMaxLevelsInPractice),
               OptionParse::bad;
      o.levels = static_cast<uint32_t>(n);
    }
  } else if (a == "--effort") {
    if (!parse_int(v, 1, 22, n)) return error = "--effort needs a whole number from 1 to 22", OptionParse::bad;
    o.effort = static_cast<int>(n);
  } else if (a == "--surface") {
    if (v == "auto") o.control.surface = SurfaceMode::automatic;
    else if (v == "closed") o.control.surface = SurfaceMode::closed;
    else if (v == "open") o.control.surface = SurfaceMode::open;
    else return error = "--surface needs closed, open or auto", OptionParse::bad;
  } else if (a == "--crease-angle") {
    if (v == "off") o.creases.angle_degrees = 0;
    else if (!parse_double(v, x) || !(x >= 1 && x <= 179))
      return error = "--crease-angle needs a number of degrees from 1 to 179, or off", OptionParse::bad;
    else o.creases.angle_degrees = x;
  } else if (a == "--step") {
    if (!parse_double(v, x) || !(x > 0 && x < 1e30)) return error = "--step needs a positive number", OptionParse::bad;
    o.step = x;
  } else {
    if (!parse_double(v, x) || !(x >= 1e-7 && x <= 0.1)) return error = "--error needs a number from 1e-7 to 0.1", OptionParse::bad;
    o.error = x;
  }
  return OptionParse::ok;
}

}  // namespace dbss::tools

// Levels of detail as one glTF 2.0 asset (binary .glb or text .gltf), the
// form game engines and web viewers load.  A single mesh goes through
// write_mesh() (geometry_files.h) like the other formats; this header adds
// several levels in one file, for `dbss export`.
#pragma once

#include <span>
#include <string>

#include "dbss/decoder/mesh.h"
#include "dbss/format/status.h"

namespace dbss {

// One level of detail: its name (given to its node and its mesh, e.g.
// "level 3") and its mesh, not owned, which must outlive the call.
struct GltfLod {
  std::string name;
  const TriangleMesh* mesh = nullptr;
};

// How levels are stored.  draco_bits > 0: every level but the finest is
// compressed with Draco (KHR_draco_mesh_compression, that many position
// quantization bits, 1..30), which makes the extension required: viewers
// without a Draco decoder then refuse the whole file.  The finest level
// always stays plain, bit for bit.
struct GltfOptions {
  int draco_bits = 0;
};

// The whole file's bytes for `lods`, finest first.  Every level is a mesh
// of one indexed triangle primitive: positions float32 (bit for bit those of
// the TriangleMesh, with their exact min/max), indices uint16 when every
// index fits (at most 65,534, since 65,535 is the primitive-restart value)
// and uint32 otherwise, in one buffer.  Each level has a node named after
// it; the scene holds only the finest level's node, which carries the
// MSFT_lod extension listing the coarser nodes in order, with
// MSFT_screencoverage hints in its extras (see gltf_screen_coverage), so a
// viewer without the extension shows the finest level and ignores the rest.
// No normals, texture coordinates or materials are written: viewers shade
// the default material flat.  `binary`: GLB, else glTF text with the buffer
// embedded as a base64 data URI.  invalid_argument when `lods` is empty, a
// mesh is null or has no triangles or an index past its vertices, or the
// result would pass GLB's 4 GiB limit; `options` as GltfOptions says.
Result<std::string> gltf_bytes(std::span<const GltfLod> lods, bool binary, const GltfOptions& options = {});

// Writes gltf_bytes(lods, ...) atomically to `path`, GLB for .glb and text
// for .gltf (case-insensitive); invalid_argument naming the path for
// another extension.
Status write_gltf_lods(const std::string& path, std::span<const GltfLod> lods, const GltfOptions& options = {});

// The MSFT_screencoverage hints for levels of `triangle_counts` triangles,
// finest first: one value per level, non-increasing, the last 0 (the
// coarsest level is never culled).  Level k is shown while the object covers
// at least value k of the screen's area; value k is where level k+1's
// triangles would average about 4 pixels each on a 1920x1080 screen (half of
// them facing the viewer), capped to halve at least from one level to the
// next so every level gets a range.  A hint for the viewer, not geometry.
std::vector<double> gltf_screen_coverage(std::span<const size_t> triangle_counts);

}  // namespace dbss

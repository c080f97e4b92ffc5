// tinygltf (Debian's libtinygltf-dev, header-only) with the configuration
// every io source uses: no image decoding or encoding (dbss carries
// geometry only, so no stb), no reading of external image files, and
// nlohmann-json (nlohmann-json3-dev) for JSON.  tiny_gltf_impl.cpp compiles
// the implementation once into dbss_io, so consumers link nothing extra.
#pragma once

#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>

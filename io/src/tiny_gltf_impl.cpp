// The one translation unit holding tinygltf's implementation (see tiny_gltf.h).
#define TINYGLTF_IMPLEMENTATION
#include "tiny_gltf.h"

// The one translation unit holding tinygltf's implementation (see tinygltf_config.h).
#define TINYGLTF_IMPLEMENTATION
#include "tinygltf_config.h"

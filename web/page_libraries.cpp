// The implementations of Debian's header-only mesh readers, which the native build links as
// libraries (libtinyobjloader, libtinygltf). The page decodes no images inside glTF files
// (TINYGLTF_NO_STB_IMAGE, for the whole page: web/CMakeLists.txt).
#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>

#define TINYGLTF_IMPLEMENTATION
#include <tiny_gltf.h>

// tinygltf's implementation for the WebAssembly build (the native build links
// Debian's libtinygltf). phedra writes no images, so the image codecs stay out.
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>

// tinygltf still refers to its image callbacks; phedra never reads or writes an image.
namespace tinygltf {
bool LoadImageData(Image*, const int, std::string* err, std::string*, int, int, const unsigned char*, int, void*) {
  if (err) *err = "phedra's WebAssembly build reads no images";
  return false;
}
bool WriteImageData(const std::string*, const std::string*, const Image*, bool, std::string*, void*) { return false; }
}  // namespace tinygltf

// One glTF accessor read element by element, its range checked against its buffer view and buffer
// when it is opened: a count or offset from the file never reaches an allocation or a read
// unchecked.
#pragma once

#include <tiny_gltf.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>

#include "absl/status/statusor.h"

namespace aperture {

class AccessorReader {
 public:
  // Accessor `index` of `model`; errors name `where` and the accessor.
  static absl::StatusOr<AccessorReader> Open(const tinygltf::Model& model, int index,
                                             const std::string& where);

  size_t count() const { return count_; }
  int components() const { return components_; }
  bool is_float() const { return type_ == TINYGLTF_COMPONENT_TYPE_FLOAT; }

  // Component c of element i; normalized integers in [0, 1] (uvs), others as they are.
  double At(size_t i, int c) const {
    const unsigned char* p = base_ + i * stride_ + static_cast<size_t>(c) * component_size_;
    switch (type_) {
      case TINYGLTF_COMPONENT_TYPE_FLOAT: {
        float f;
        std::memcpy(&f, p, sizeof f);
        return f;
      }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        return normalized_ ? p[0] / 255.0 : p[0];
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        uint16_t v;
        std::memcpy(&v, p, sizeof v);
        return normalized_ ? v / 65535.0 : v;
      }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
        uint32_t v;
        std::memcpy(&v, p, sizeof v);
        return v;
      }
      case TINYGLTF_COMPONENT_TYPE_BYTE:
        return normalized_ ? std::max(static_cast<int8_t>(p[0]) / 127.0, -1.0)
                           : static_cast<int8_t>(p[0]);
      case TINYGLTF_COMPONENT_TYPE_SHORT: {
        int16_t v;
        std::memcpy(&v, p, sizeof v);
        return normalized_ ? std::max(v / 32767.0, -1.0) : v;
      }
      default:
        return 0;
    }
  }

 private:
  const unsigned char* base_ = nullptr;
  size_t count_ = 0, stride_ = 0;
  int components_ = 0, component_size_ = 0, type_ = 0;
  bool normalized_ = false;
};

}  // namespace aperture

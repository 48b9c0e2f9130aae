#include "gltf_accessor.h"

#include "absl/strings/str_cat.h"

namespace aperture {
namespace {

absl::Status Invalid(const std::string& where, const std::string& what) {
  return absl::InvalidArgumentError(absl::StrCat(where, ": ", what));
}

}  // namespace

absl::StatusOr<AccessorReader> AccessorReader::Open(const tinygltf::Model& model, int index,
                                                    const std::string& where) {
  if (index < 0 || index >= static_cast<int>(model.accessors.size()))
    return Invalid(where, absl::StrCat("accessor ", index, " does not exist"));
  const tinygltf::Accessor& a = model.accessors[index];
  const std::string at = absl::StrCat(where, " (accessors[", index, "])");
  if (a.sparse.isSparse) return Invalid(at, "sparse accessors are not supported");
  if (a.bufferView < 0 || a.bufferView >= static_cast<int>(model.bufferViews.size()))
    return Invalid(at, "has no buffer view");
  const tinygltf::BufferView& view = model.bufferViews[a.bufferView];
  if (view.buffer < 0 || view.buffer >= static_cast<int>(model.buffers.size()))
    return Invalid(at, "its buffer view has no buffer");
  const std::vector<unsigned char>& data = model.buffers[view.buffer].data;
  AccessorReader r;
  r.components_ = tinygltf::GetNumComponentsInType(static_cast<uint32_t>(a.type));
  r.component_size_ = tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(a.componentType));
  if (r.components_ <= 0 || r.component_size_ <= 0)
    return Invalid(at, "has an unknown type or component type");
  r.type_ = a.componentType;
  r.normalized_ = a.normalized;
  r.count_ = a.count;
  const size_t element = static_cast<size_t>(r.components_) * r.component_size_;
  r.stride_ = view.byteStride != 0 ? view.byteStride : element;
  if (r.stride_ < element) return Invalid(at, "byteStride is smaller than an element");
  if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset)
    return Invalid(at, absl::StrCat("buffer view ", a.bufferView, " (", view.byteOffset, " + ",
                                    view.byteLength, " bytes) goes beyond its buffer of ",
                                    data.size(), " bytes"));
  if (a.count > 0) {
    const size_t last = a.byteOffset + (a.count - 1) * r.stride_ + element;
    if (a.byteOffset > view.byteLength || (a.count - 1) > view.byteLength / r.stride_ ||
        last > view.byteLength)
      return Invalid(
          at, absl::StrCat(a.count, " elements from byte ", a.byteOffset, " go beyond buffer view ",
                           a.bufferView, " of ", view.byteLength, " bytes"));
  }
  r.base_ = data.data() + view.byteOffset + a.byteOffset;
  return r;
}

}  // namespace aperture

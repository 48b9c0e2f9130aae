// The bytes that containers hold (their capacity): what a frame's working memory is made of
// (render/frame_memory.h).
#pragma once

#include <cstddef>
#include <vector>

namespace aperture {

template <class... T>
size_t HeldBytes(const std::vector<T>&... v) {
  return (size_t{0} + ... + (v.capacity() * sizeof(T)));
}

// A hash map's slots (absl's flat maps: a control byte and a slot each).
template <class Map>
size_t HeldMapBytes(const Map& map) {
  return map.capacity() * (sizeof(typename Map::value_type) + 1);
}

}  // namespace aperture

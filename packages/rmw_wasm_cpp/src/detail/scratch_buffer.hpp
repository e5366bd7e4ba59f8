// Copyright 2026 The colcon-wasm authors
//
// Licensed under the Apache License, Version 2.0 (the "License");
// you may not use this file except in compliance with the License.
// You may obtain a copy of the License at
//
//     http://www.apache.org/licenses/LICENSE-2.0
//
// Unless required by applicable law or agreed to in writing, software
// distributed under the License is distributed on an "AS IS" BASIS,
// WITHOUT WARRANTIES OR CONDITIONS OF ANY KIND, either express or implied.
// See the License for the specific language governing permissions and
// limitations under the License.

#ifndef DETAIL__SCRATCH_BUFFER_HPP_
#define DETAIL__SCRATCH_BUFFER_HPP_

#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "wasm_cpp/types.hpp"

namespace rmw_wasm_cpp
{

/// A growable byte buffer that is reused between messages (one per thread).
/**
 * take() copies a message from the bus straight into this buffer (through
 * allocator()), and publish() serializes into it, so that steady traffic
 * allocates nothing. It never shrinks; it is not zero-filled.
 */
class ScratchBuffer final
{
public:
  ScratchBuffer() = default;
  ScratchBuffer(const ScratchBuffer &) = delete;
  ScratchBuffer & operator=(const ScratchBuffer &) = delete;
  ~ScratchBuffer() {std::free(data_);}

  /// Make room for `size` bytes; returns the storage, or null when out of memory.
  uint8_t * reserve(size_t size)
  {
    if (size > capacity_) {
      size_t capacity = capacity_ < 256 ? 256 : capacity_;
      while (capacity < size) {
        capacity = capacity * 2 < capacity ? size : capacity * 2;
      }
      void * grown = std::realloc(data_, capacity);
      if (grown == nullptr) {
        return nullptr;
      }
      data_ = static_cast<uint8_t *>(grown);
      capacity_ = capacity;
    }
    return data_;
  }

  /// The storage (null before the first reserve()).
  uint8_t * data() {return data_;}

  /// A wasm_cpp allocator that hands out this buffer (take() writes into it).
  wasm_cpp::Allocator allocator()
  {
    wasm_cpp::Allocator a;
    a.allocate = [](size_t size, void * state) -> void * {
        return static_cast<ScratchBuffer *>(state)->reserve(size);
      };
    a.deallocate = [](void *, void *) {};
    a.state = this;
    // A message that fits is copied here without a call to allocate().
    a.buffer = data_;
    a.capacity = capacity_;
    return a;
  }

  /// The calling thread's buffer.
  static ScratchBuffer & for_this_thread()
  {
    static thread_local ScratchBuffer buffer;
    return buffer;
  }

private:
  // malloc'd storage.
  uint8_t * data_ = nullptr;
  // Bytes allocated.
  size_t capacity_ = 0;
};

}  // namespace rmw_wasm_cpp

#endif  // DETAIL__SCRATCH_BUFFER_HPP_

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

#ifndef DETAIL__CDR_HPP_
#define DETAIL__CDR_HPP_

/// \file
/// The CDR byte stream: plain CDR (XCDR1) as Fast CDR 1.x writes it for
/// rmw_fastrtps_cpp. A stream is a 4-byte encapsulation header (`00 01 00 00`
/// for little endian) followed by the body. Every primitive is aligned to its
/// own size (at most 8), counted from the start of the body. Strings are a
/// uint32 length that includes the terminating NUL, then the bytes and the
/// NUL; wide strings a uint32 count of UTF-16 code units (no terminator),
/// then each unit as a uint32. There is no padding after the last field.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <utility>

namespace rmw_wasm_cpp
{
namespace cdr
{

/// Size of the encapsulation header.
constexpr size_t kHeaderSize = 4;

/// Encapsulation kind byte (second header byte) of big-endian plain CDR.
constexpr uint8_t kEncapsulationBigEndian = 0x00;
/// Encapsulation kind byte (second header byte) of little-endian plain CDR.
constexpr uint8_t kEncapsulationLittleEndian = 0x01;

/// Where a traversal failed and why: set once, then extended with field names on the way out.
/**
 * Sizer and Reader never throw: on the first problem they record it here,
 * every later operation does nothing, and the traversal returns early,
 * prefixing the path of the field it was in ("header.frame_id").
 */
class Failure final
{
public:
  /// True while nothing failed.
  bool ok() const {return reason_.empty();}

  /// Record the first failure; later calls are ignored.
  void fail(std::string reason)
  {
    if (reason_.empty()) {
      reason_ = reason.empty() ? std::string("unknown error") : std::move(reason);
    }
  }

  /// Prefix the field path with `name` (called by each enclosing level).
  void add_field(const char * name)
  {
    path_ = path_.empty() ? std::string(name) :
      (path_[0] == '[' ? std::string(name) + path_ : std::string(name) + "." + path_);
  }

  /// Prefix the field path with an element index.
  void add_index(size_t index)
  {
    path_ = "[" + std::to_string(index) + "]" + (path_.empty() || path_[0] == '[' ? "" : ".") + path_;
  }

  /// "field 'a.b': reason", or the reason alone when no field is known.
  std::string message() const
  {
    return path_.empty() ? reason_ : "field '" + path_ + "': " + reason_;
  }

private:
  // What went wrong, empty while ok.
  std::string reason_;
  // Dotted path of the field where it went wrong.
  std::string path_;
};

/// Counts the bytes a message needs; has the same interface as Writer.
class Sizer final
{
public:
  /// Skip to the next multiple of `alignment` (a power of two).
  void align(size_t alignment) {pos_ = (pos_ + alignment - 1) & ~(alignment - 1);}

  /// Account for one primitive of `size` bytes (1, 2, 4 or 8) or 16 (long double, 8-aligned).
  void primitive(const void *, size_t size) {align(size > 8 ? 8 : size); pos_ += size;}

  /// Account for `count` primitives of `size` bytes each.
  void primitives(const void *, size_t size, size_t count)
  {
    if (count > 0) {align(size > 8 ? 8 : size); pos_ += size * count;}
  }

  /// Account for one boolean.
  void boolean(bool) {pos_ += 1;}

  /// Account for a uint32 (lengths and counts).
  void uint32(uint32_t) {align(4); pos_ += 4;}

  /// Account for a string of `length` bytes (without its NUL).
  void string(const char *, size_t length) {uint32(0); pos_ += length + 1;}

  /// Account for a wide string of `length` UTF-16 units.
  void wstring(const uint16_t *, size_t length) {uint32(0); pos_ += 4 * length;}

  /// Bytes of body counted so far.
  size_t body_size() const {return pos_;}

  /// The failure record (a message that cannot be serialized, e.g. over a bound).
  Failure & failure() {return failure_;}

  /// True while nothing failed.
  bool ok() const {return failure_.ok();}

private:
  // Body bytes so far.
  size_t pos_ = 0;
  // Set when the message cannot be serialized.
  Failure failure_;
};

/// Writes a stream into a buffer sized by Sizer (header included); never fails.
class Writer final
{
public:
  /// Write the little-endian header into `buffer` and get ready to write the body after it.
  explicit Writer(uint8_t * buffer)
  : body_(buffer + kHeaderSize)
  {
    buffer[0] = 0x00;
    buffer[1] = kEncapsulationLittleEndian;
    buffer[2] = 0x00;
    buffer[3] = 0x00;
  }

  /// Write zero bytes up to the next multiple of `alignment`.
  void align(size_t alignment)
  {
    const size_t aligned = (pos_ + alignment - 1) & ~(alignment - 1);
    while (pos_ < aligned) {
      body_[pos_++] = 0;
    }
  }

  /// Write one primitive of `size` bytes (native little endian).
  void primitive(const void * value, size_t size)
  {
    align(size > 8 ? 8 : size);
    std::memcpy(body_ + pos_, value, size);
    pos_ += size;
  }

  /// Write `count` primitives of `size` bytes, stored contiguously at `values`.
  void primitives(const void * values, size_t size, size_t count)
  {
    if (count == 0) {
      return;
    }
    align(size > 8 ? 8 : size);
    std::memcpy(body_ + pos_, values, size * count);
    pos_ += size * count;
  }

  /// Write a boolean as one byte, 0 or 1.
  void boolean(bool value) {body_[pos_++] = value ? 1 : 0;}

  /// Write a uint32.
  void uint32(uint32_t value) {primitive(&value, sizeof(value));}

  /// Write a string: length with NUL, bytes, NUL.
  void string(const char * data, size_t length)
  {
    uint32(static_cast<uint32_t>(length + 1));
    if (length > 0) {
      std::memcpy(body_ + pos_, data, length);
    }
    pos_ += length;
    body_[pos_++] = 0;
  }

  /// Write a wide string: count, then each UTF-16 unit as a uint32.
  void wstring(const uint16_t * data, size_t length)
  {
    uint32(static_cast<uint32_t>(length));
    for (size_t i = 0; i < length; ++i) {
      const uint32_t unit = data[i];
      std::memcpy(body_ + pos_, &unit, 4);
      pos_ += 4;
    }
  }

  /// Bytes of body written so far.
  size_t body_size() const {return pos_;}

  /// A writer never fails (the Sizer pass checked the message).
  bool ok() const {return true;}

  /// Not used by a writer; present so that traversals compile for both.
  Failure & failure() {return unused_;}

private:
  // First byte after the header.
  uint8_t * body_;
  // Body bytes written so far.
  size_t pos_ = 0;
  // Never set.
  Failure unused_;
};

/// Reads a stream, checking every access against its end.
/**
 * On the first problem the reader records a Failure and every later read
 * returns zeros, so that a traversal can stop at its next check.
 */
class Reader final
{
public:
  /// Check the header of `data` (`size` bytes) and get ready to read the body.
  Reader(const uint8_t * data, size_t size)
  {
    if (data == nullptr || size < kHeaderSize) {
      failure_.fail(
        "CDR stream of " + std::to_string(size) +
        " bytes is shorter than the 4-byte encapsulation header");
      return;
    }
    if (data[0] != 0x00 ||
      (data[1] != kEncapsulationLittleEndian && data[1] != kEncapsulationBigEndian))
    {
      char header[16];
      std::snprintf(
        header, sizeof(header), "%02x %02x %02x %02x", data[0], data[1], data[2], data[3]);
      failure_.fail(
        std::string("CDR encapsulation header ") + header +
        " is not plain CDR (expected 00 01 00 00 or 00 00 00 00)");
      return;
    }
    swap_ = data[1] == kEncapsulationBigEndian;
    body_ = data + kHeaderSize;
    size_ = size - kHeaderSize;
  }

  /// True while nothing failed.
  bool ok() const {return failure_.ok();}

  /// The failure record.
  Failure & failure() {return failure_;}

  /// Skip to the next multiple of `alignment`.
  void align(size_t alignment)
  {
    const size_t aligned = (pos_ + alignment - 1) & ~(alignment - 1);
    if (need(aligned - pos_, "padding")) {
      pos_ = aligned;
    }
  }

  /// Read one primitive of `size` bytes into `value` (zeros after a failure).
  void primitive(void * value, size_t size)
  {
    align(size > 8 ? 8 : size);
    if (!need(size, "a value")) {
      std::memset(value, 0, size);
      return;
    }
    copy_swapped(value, body_ + pos_, size, 1);
    pos_ += size;
  }

  /// Read `count` primitives of `size` bytes into contiguous memory at `values`.
  void primitives(void * values, size_t size, size_t count)
  {
    if (count == 0) {
      return;
    }
    align(size > 8 ? 8 : size);
    if (!need(size * count, "an array")) {
      return;
    }
    copy_swapped(values, body_ + pos_, size, count);
    pos_ += size * count;
  }

  /// Read a boolean (any non-zero byte is true).
  bool boolean()
  {
    if (!need(1, "a boolean")) {
      return false;
    }
    return body_[pos_++] != 0;
  }

  /// Read a uint32.
  uint32_t uint32()
  {
    uint32_t value = 0;
    primitive(&value, sizeof(value));
    return value;
  }

  /// Read an element count and check that `count` elements of at least
  /// `min_element_size` bytes can still follow (guards against huge allocations).
  size_t count(size_t min_element_size)
  {
    const uint64_t n = uint32();
    if (!ok()) {
      return 0;
    }
    if (n * min_element_size > size_ - pos_) {
      failure_.fail(
        "element count " + std::to_string(n) + " at byte " +
        std::to_string(kHeaderSize + pos_ - 4) + " needs at least " +
        std::to_string(n * min_element_size) + " bytes but only " +
        std::to_string(size_ - pos_) + " remain");
      return 0;
    }
    return static_cast<size_t>(n);
  }

  /// Read a string; `*data` then points into the stream and `*length` excludes the NUL.
  void string(const char ** data, size_t * length)
  {
    *data = "";
    *length = 0;
    const uint32_t n = uint32();
    if (!need(n, "a string")) {
      return;
    }
    *data = reinterpret_cast<const char *>(body_ + pos_);
    *length = (n > 0 && body_[pos_ + n - 1] == 0) ? n - 1 : n;
    pos_ += n;
  }

  /// Read a wide string's unit count; then call wstring_unit() that many times.
  size_t wstring_length() {return count(4);}

  /// Read one UTF-16 unit of a wide string (stored as a uint32).
  uint16_t wstring_unit()
  {
    uint32_t unit = 0;
    if (!need(4, "a wide string")) {
      return 0;
    }
    copy_swapped(&unit, body_ + pos_, 4, 1);
    pos_ += 4;
    return static_cast<uint16_t>(unit);
  }

  /// Body bytes read so far.
  size_t body_position() const {return pos_;}

  /// Body bytes not read yet.
  size_t remaining() const {return size_ - pos_;}

private:
  // True when n more bytes can be read; records a failure otherwise.
  bool need(size_t n, const char * what)
  {
    if (!ok()) {
      return false;
    }
    if (n > size_ - pos_) {
      failure_.fail(
        std::string("CDR stream ends while reading ") + what + " at byte " +
        std::to_string(kHeaderSize + pos_) + ": " + std::to_string(n) +
        " bytes needed, " + std::to_string(size_ - pos_) + " left");
      return false;
    }
    return true;
  }

  // Copy count values of size bytes, reversing each when the stream is big endian.
  void copy_swapped(void * dst, const uint8_t * src, size_t size, size_t count) const
  {
    if (!swap_ || size == 1) {
      std::memcpy(dst, src, size * count);
      return;
    }
    auto out = static_cast<uint8_t *>(dst);
    for (size_t i = 0; i < count; ++i) {
      for (size_t b = 0; b < size; ++b) {
        out[i * size + b] = src[i * size + size - 1 - b];
      }
    }
  }

  // First byte after the header.
  const uint8_t * body_ = nullptr;
  // Body size in bytes.
  size_t size_ = 0;
  // Body bytes read so far.
  size_t pos_ = 0;
  // True for a big-endian stream.
  bool swap_ = false;
  // Set on the first problem.
  Failure failure_;
};

}  // namespace cdr
}  // namespace rmw_wasm_cpp

#endif  // DETAIL__CDR_HPP_

#pragma once
// Plain values packed into bytes: a task's result as it crosses between the processes of one
// run (core/task_farm.hpp). The processes share one binary and one machine type, so a value
// travels as its own bytes (doubles exactly, not through text).
#include <cstring>
#include <string>
#include <type_traits>

#include "ddaslope/core/errors.hpp"

namespace ddaslope {

class BytePacker {
 public:
  template <class T>
  BytePacker& put(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>, "only plain values travel as bytes");
    bytes_.append(reinterpret_cast<const char*>(&value), sizeof(T));
    return *this;
  }
  BytePacker& put(const std::string& text) {
    put(text.size());
    bytes_ += text;
    return *this;
  }
  const std::string& bytes() const { return bytes_; }

 private:
  std::string bytes_;
};

class ByteUnpacker {
 public:
  explicit ByteUnpacker(const std::string& bytes) : bytes_(bytes) {}
  template <class T>
  T get() {
    static_assert(std::is_trivially_copyable_v<T>, "only plain values travel as bytes");
    DDASLOPE_ASSERT(at_ + sizeof(T) <= bytes_.size(), "a task's result is shorter than its reader expects");
    T value;
    std::memcpy(&value, bytes_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return value;
  }
  std::string getString() {
    const size_t n = get<size_t>();
    DDASLOPE_ASSERT(at_ + n <= bytes_.size(), "a task's result is shorter than its reader expects");
    std::string s = bytes_.substr(at_, n);
    at_ += n;
    return s;
  }

 private:
  const std::string& bytes_;
  size_t at_ = 0;
};

}  // namespace ddaslope

#pragma once
// OpenEXR streams over bytes in memory, so that EXR files are encoded and decoded without
// OpenEXR touching the file system (writes then go through writeFileAtomically).
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/Iex.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

namespace cloudlut::io {

// An output stream that collects everything written (with seeks) in a string.
class MemoryOStream : public Imf::OStream {
 public:
  explicit MemoryOStream(const std::string& name) : Imf::OStream(name.c_str()) {}

  // Writes n bytes at the current position, growing the buffer as needed.
  void write(const char c[], int n) override {
    const std::size_t count = static_cast<std::size_t>(std::max(n, 0));
    if (pos_ + count > bytes_.size()) bytes_.resize(pos_ + count);
    std::memcpy(bytes_.data() + pos_, c, count);
    pos_ += count;
  }
  uint64_t tellp() override { return pos_; }
  void seekp(uint64_t pos) override { pos_ = static_cast<std::size_t>(pos); }

  const std::string& bytes() const { return bytes_; }

 private:
  std::string bytes_;
  std::size_t pos_ = 0;
};

// An input stream reading from bytes the caller keeps alive; reading past the end throws.
class MemoryIStream : public Imf::IStream {
 public:
  MemoryIStream(const std::string& name, std::string_view bytes)
      : Imf::IStream(name.c_str()), bytes_(bytes) {}

  // Copies n bytes from the current position; returns false once the last byte has been read.
  bool read(char c[], int n) override {
    const std::size_t count = static_cast<std::size_t>(std::max(n, 0));
    if (pos_ > bytes_.size() || count > bytes_.size() - pos_)
      throw Iex::InputExc("unexpected end of file");
    std::memcpy(c, bytes_.data() + pos_, count);
    pos_ += count;
    return pos_ < bytes_.size();
  }
  uint64_t tellg() override { return pos_; }
  void seekg(uint64_t pos) override { pos_ = static_cast<std::size_t>(pos); }

 private:
  std::string_view bytes_;
  std::size_t pos_ = 0;
};

}  // namespace cloudlut::io

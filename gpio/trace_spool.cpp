#include "gpio/trace_spool.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace stepmod::gpio {

namespace {
constexpr std::size_t kWriteBuffer = std::size_t{4} << 20;  // 4 MB: ~260k records per write
constexpr std::size_t kReadBatch = 1u << 16;
}  // namespace

TraceSpool::TraceSpool(std::string path) : path_(std::move(path)), buffer_(kWriteBuffer) {
  f_ = std::fopen(path_.c_str(), "w+b");
  if (f_ == nullptr) {
    throw std::runtime_error("trace spool '" + path_ + "': cannot create: " + std::strerror(errno));
  }
  std::setvbuf(f_, buffer_.data(), _IOFBF, buffer_.size());
}

TraceSpool::~TraceSpool() {
  if (f_ != nullptr) std::fclose(f_);
  ::unlink(path_.c_str());
}

void TraceSpool::append(const TraceRecord& r) {
  if (std::fwrite(&r, sizeof r, 1, f_) != 1) failed_ = true;
  ++count_;
}

bool TraceSpool::finish() {
  if (std::fflush(f_) != 0) failed_ = true;
  return !failed_ && std::ferror(f_) == 0;
}

TraceSpool::Reader::Reader(const std::string& path) : buf_(kReadBatch) {
  f_ = std::fopen(path.c_str(), "rb");
  if (f_ == nullptr) {
    throw std::runtime_error("trace spool '" + path + "': cannot read: " + std::strerror(errno));
  }
}

TraceSpool::Reader::~Reader() {
  if (f_ != nullptr) std::fclose(f_);
}

const TraceRecord* TraceSpool::Reader::next() {
  if (pos_ == len_) {
    len_ = std::fread(buf_.data(), sizeof(TraceRecord), buf_.size(), f_);
    pos_ = 0;
    if (len_ == 0) return nullptr;
  }
  return &buf_[pos_++];
}

}  // namespace stepmod::gpio

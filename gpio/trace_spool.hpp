#pragma once
// A binary spool of TraceRecords: the trace thread appends what it drains from a trace ring
// (a buffered fwrite of 16-byte records, tens of millions a second), and the VCD is written from
// it when the daemon stops. Formatting text while the pulse thread produces 2 M records/s is what
// made the old streaming writer fall behind and its ring overflow (issue 12: a third of a 1 MHz
// move lost).
#include <cstdint>
#include <cstdio>
#include <span>
#include <string>
#include <vector>

#include "core/trace_record.hpp"

namespace stepmod::gpio {

class TraceSpool {
 public:
  // Creates (truncates) `path`; throws std::runtime_error naming it if that fails.
  explicit TraceSpool(std::string path);
  ~TraceSpool();  // closes and removes the file
  TraceSpool(const TraceSpool&) = delete;
  TraceSpool& operator=(const TraceSpool&) = delete;

  void append(const TraceRecord& r);
  std::uint64_t size() const noexcept { return count_; }
  // Ends writing (flush); false if any write failed (disk full...).
  bool finish();

  // Reads the records back in order, `batch` at a time; an empty span at the end.
  class Reader {
   public:
    explicit Reader(const std::string& path);
    ~Reader();
    Reader(const Reader&) = delete;
    Reader& operator=(const Reader&) = delete;
    // The next record, or nullptr at the end.
    const TraceRecord* next();

   private:
    std::FILE* f_ = nullptr;
    std::vector<TraceRecord> buf_;
    std::size_t pos_ = 0;
    std::size_t len_ = 0;
  };
  const std::string& path() const noexcept { return path_; }

 private:
  std::string path_;
  std::FILE* f_ = nullptr;
  std::vector<char> buffer_;  // stdio buffer: few large writes
  std::uint64_t count_ = 0;
  bool failed_ = false;
};

}  // namespace stepmod::gpio

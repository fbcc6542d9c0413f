#pragma once
// A flat, ordered JSON object for command results (`--json`), so that layers above io can
// print JSON without seeing the JSON library.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace ddaslope::io {

class JsonRecord {
 public:
  JsonRecord();
  ~JsonRecord();
  JsonRecord(const JsonRecord&) = delete;
  JsonRecord& operator=(const JsonRecord&) = delete;
  JsonRecord& set(const std::string& key, double value);
  JsonRecord& set(const std::string& key, int value);
  JsonRecord& set(const std::string& key, std::uint64_t value);  ///< a seed, exactly
  JsonRecord& set(const std::string& key, bool value);
  JsonRecord& set(const std::string& key, const std::string& value);
  JsonRecord& set(const std::string& key, const char* value) { return set(key, std::string(value)); }
  JsonRecord& set(const std::string& key, const std::vector<double>& values);  ///< NaN: null
  JsonRecord& set(const std::string& key, const std::vector<std::string>& values);
  JsonRecord& set(const std::string& key, const JsonRecord& object);
  /// Appends `item` to the array at `key` (created if missing).
  JsonRecord& append(const std::string& key, const JsonRecord& item);
  std::string dump() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace ddaslope::io

#include "ddaslope/io/json_record.hpp"

#include <nlohmann/json.hpp>

namespace ddaslope::io {

struct JsonRecord::Impl {
  nlohmann::ordered_json j = nlohmann::ordered_json::object();
};

JsonRecord::JsonRecord() : impl_(std::make_unique<Impl>()) {}
JsonRecord::~JsonRecord() = default;
JsonRecord& JsonRecord::set(const std::string& k, double v) { impl_->j[k] = v; return *this; }
JsonRecord& JsonRecord::set(const std::string& k, int v) { impl_->j[k] = v; return *this; }
JsonRecord& JsonRecord::set(const std::string& k, std::uint64_t v) { impl_->j[k] = v; return *this; }
JsonRecord& JsonRecord::set(const std::string& k, bool v) { impl_->j[k] = v; return *this; }
JsonRecord& JsonRecord::set(const std::string& k, const std::string& v) { impl_->j[k] = v; return *this; }
JsonRecord& JsonRecord::set(const std::string& k, const std::vector<double>& v) { impl_->j[k] = v; return *this; }
JsonRecord& JsonRecord::set(const std::string& k, const std::vector<std::string>& v) { impl_->j[k] = v; return *this; }
JsonRecord& JsonRecord::set(const std::string& k, const JsonRecord& o) { impl_->j[k] = o.impl_->j; return *this; }
JsonRecord& JsonRecord::append(const std::string& k, const JsonRecord& item) {
  impl_->j[k].push_back(item.impl_->j);
  return *this;
}
std::string JsonRecord::dump() const { return impl_->j.dump(2); }

}  // namespace ddaslope::io

// A small JSON writer for reports and logs: values are built as a tree and serialised with
// keys in insertion order, whole numbers as integers and other doubles in their shortest
// round-trip form (std::to_chars). Non-finite numbers are a broken invariant (reports never
// hold NaN), checked on write.
#pragma once

#include <cstdint>
#include <initializer_list>
#include <map>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include <glm/glm.hpp>

#include "hemirad/visibility.h"

namespace hemirad {

class HEMIRAD_API Json {
  public:
    Json() : v_(nullptr) {}
    Json(std::nullptr_t) : v_(nullptr) {}
    Json(bool b) : v_(b) {}
    Json(int x) : v_(double(x)) {}
    Json(long x) : v_(double(x)) {}
    Json(long long x) : v_(double(x)) {}
    Json(unsigned x) : v_(double(x)) {}
    Json(unsigned long x) : v_(double(x)) {}
    Json(unsigned long long x) : v_(double(x)) {}
    Json(double x) : v_(x) {}
    Json(const char* s) : v_(std::string(s)) {}
    Json(std::string s) : v_(std::move(s)) {}
    Json(const glm::dvec3& v) : Json(Json::array({v.x, v.y, v.z})) {}

    static Json object() {
        Json j;
        j.v_ = Object{};
        return j;
    }
    static Json array(std::initializer_list<Json> items = {}) {
        Json j;
        j.v_ = Array(items);
        return j;
    }
    /// Object member (created if missing; keeps insertion order).
    Json& operator[](const std::string& key);
    void push_back(Json item);

    std::string dump(int indent = 2) const;

  private:
    using Object = std::vector<std::pair<std::string, Json>>;
    using Array = std::vector<Json>;
    void write(std::string& out, int indent, int depth) const;
    std::variant<std::nullptr_t, bool, double, std::string, Array, Object> v_;
};

} // namespace hemirad

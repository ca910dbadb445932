#include "hemirad/json.h"

#include <charconv>
#include <cmath>
#include <cstdio>

#include "hemirad/error.h"

namespace hemirad {

Json& Json::operator[](const std::string& key) {
    if (std::holds_alternative<std::nullptr_t>(v_)) v_ = Object{};
    auto& obj = std::get<Object>(v_);
    for (auto& kv : obj)
        if (kv.first == key) return kv.second;
    obj.emplace_back(key, Json());
    return obj.back().second;
}

void Json::push_back(Json item) {
    if (std::holds_alternative<std::nullptr_t>(v_)) v_ = Array{};
    std::get<Array>(v_).push_back(std::move(item));
}

namespace {

void write_string(std::string& out, const std::string& s) {
    out += '"';
    for (unsigned char c : s) {
        switch (c) {
        case '"':
            out += "\\\"";
            break;
        case '\\':
            out += "\\\\";
            break;
        case '\n':
            out += "\\n";
            break;
        case '\t':
            out += "\\t";
            break;
        case '\r':
            out += "\\r";
            break;
        default:
            if (c < 0x20) {
                char buf[8];
                std::snprintf(buf, sizeof buf, "\\u%04x", c);
                out += buf;
            } else {
                out += char(c);
            }
        }
    }
    out += '"';
}

} // namespace

void Json::write(std::string& out, int indent, int depth) const {
    const auto newline = [&](int d) {
        if (indent <= 0) return;
        out += '\n';
        out.append(std::size_t(indent * d), ' ');
    };
    if (std::holds_alternative<std::nullptr_t>(v_))
        out += "null";
    else if (auto* b = std::get_if<bool>(&v_))
        out += *b ? "true" : "false";
    else if (auto* x = std::get_if<double>(&v_)) {
        HEMIRAD_CHECK(std::isfinite(*x));
        // Whole numbers (counts, sizes) as integers; others in the shortest form that reads
        // back as the same double (std::to_chars: 0.1, not 0.10000000000000001).
        char buf[32];
        if (*x == std::floor(*x) && std::abs(*x) < 1e15) {
            std::snprintf(buf, sizeof buf, "%.0f", *x);
            out += buf;
        } else {
            const std::to_chars_result r = std::to_chars(buf, buf + sizeof buf, *x);
            HEMIRAD_CHECK(r.ec == std::errc());
            out.append(buf, r.ptr);
        }
    } else if (auto* s = std::get_if<std::string>(&v_))
        write_string(out, *s);
    else if (auto* a = std::get_if<Array>(&v_)) {
        out += '[';
        bool scalars = true;
        for (const Json& j : *a)
            if (std::holds_alternative<Array>(j.v_) || std::holds_alternative<Object>(j.v_))
                scalars = false;
        for (std::size_t i = 0; i < a->size(); ++i) {
            if (i) out += scalars || indent <= 0 ? ", " : ",";
            if (!scalars) newline(depth + 1);
            (*a)[i].write(out, indent, depth + 1);
        }
        if (!scalars && !a->empty()) newline(depth);
        out += ']';
    } else {
        const auto& o = std::get<Object>(v_);
        out += '{';
        for (std::size_t i = 0; i < o.size(); ++i) {
            if (i) out += ',';
            newline(depth + 1);
            write_string(out, o[i].first);
            out += indent > 0 ? ": " : ":";
            o[i].second.write(out, indent, depth + 1);
        }
        if (!o.empty()) newline(depth);
        out += '}';
    }
}

std::string Json::dump(int indent) const {
    std::string out;
    write(out, indent, 0);
    return out;
}

} // namespace hemirad

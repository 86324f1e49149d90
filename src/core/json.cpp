#include "core/json.h"

#include <cmath>
#include <cstdio>

namespace amrvk {

std::string jsonEscape(std::string_view s) {
    std::string out;
    out.reserve(s.size() + 2);
    for (char c : s) {
        switch (c) {
            case '"': out += "\\\""; break;
            case '\\': out += "\\\\"; break;
            case '\n': out += "\\n"; break;
            case '\r': out += "\\r"; break;
            case '\t': out += "\\t"; break;
            default:
                if (static_cast<unsigned char>(c) < 0x20) {
                    char buf[8];
                    std::snprintf(buf, sizeof buf, "\\u%04x", c);
                    out += buf;
                } else {
                    out += c;
                }
        }
    }
    return out;
}

void JsonWriter::separate() {
    if (mAfterKey) {
        mAfterKey = false;
        return;
    }
    if (!mFirst.empty()) {
        if (!mFirst.back()) mOut += ',';
        mFirst.back() = false;
    }
}

JsonWriter& JsonWriter::beginObject() {
    separate();
    mOut += '{';
    mFirst.push_back(true);
    return *this;
}
JsonWriter& JsonWriter::endObject() {
    mOut += '}';
    mFirst.pop_back();
    return *this;
}
JsonWriter& JsonWriter::beginArray() {
    separate();
    mOut += '[';
    mFirst.push_back(true);
    return *this;
}
JsonWriter& JsonWriter::endArray() {
    mOut += ']';
    mFirst.pop_back();
    return *this;
}
JsonWriter& JsonWriter::key(std::string_view name) {
    separate();
    mOut += '"';
    mOut += jsonEscape(name);
    mOut += "\":";
    mAfterKey = true;
    return *this;
}
JsonWriter& JsonWriter::value(double v) {
    if (!std::isfinite(v)) return null();
    separate();
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    mOut += buf;
    return *this;
}
JsonWriter& JsonWriter::value(int64_t v) {
    separate();
    mOut += std::to_string(v);
    return *this;
}
JsonWriter& JsonWriter::value(uint64_t v) {
    separate();
    mOut += std::to_string(v);
    return *this;
}
JsonWriter& JsonWriter::value(bool v) {
    separate();
    mOut += v ? "true" : "false";
    return *this;
}
JsonWriter& JsonWriter::value(std::string_view v) {
    separate();
    mOut += '"';
    mOut += jsonEscape(v);
    mOut += '"';
    return *this;
}
JsonWriter& JsonWriter::null() {
    separate();
    mOut += "null";
    return *this;
}

}  // namespace amrvk

#pragma once
// Minimal streaming JSON writer for --json outputs (one object per command, UTF-8, no NaN:
// non-finite numbers are written as null).
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace amrvk {

class JsonWriter {
public:
    JsonWriter& beginObject();
    JsonWriter& endObject();
    JsonWriter& beginArray();
    JsonWriter& endArray();
    // Starts a member of the current object; the next value call gives its value.
    JsonWriter& key(std::string_view name);
    JsonWriter& value(double v);
    JsonWriter& value(int64_t v);
    JsonWriter& value(uint64_t v);
    JsonWriter& value(int v) { return value(static_cast<int64_t>(v)); }
    JsonWriter& value(unsigned v) { return value(static_cast<uint64_t>(v)); }
    JsonWriter& value(bool v);
    JsonWriter& value(std::string_view v);
    JsonWriter& value(const char* v) { return value(std::string_view(v)); }
    JsonWriter& null();
    template <typename T>
    JsonWriter& member(std::string_view name, const T& v) {
        key(name);
        return value(v);
    }
    const std::string& str() const { return mOut; }

private:
    void separate();
    std::string mOut;
    std::vector<bool> mFirst;  // per open container: no element written yet
    bool mAfterKey = false;
};

std::string jsonEscape(std::string_view s);

}  // namespace amrvk

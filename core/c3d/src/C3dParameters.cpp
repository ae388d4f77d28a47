#include "boneless/C3dParameters.h"

#include <algorithm>
#include <stdexcept>

namespace boneless {

bool c3dNameEquals(std::string_view a, std::string_view b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i) {
        auto up = [](char c) { return (c >= 'a' && c <= 'z') ? char(c - 'a' + 'A') : c; };
        if (up(a[i]) != up(b[i])) return false;
    }
    return true;
}

namespace {
std::size_t product(const std::vector<int>& dims) {
    std::size_t n = 1;
    for (int d : dims) n *= static_cast<std::size_t>(d);
    return n;
}

std::string trimmed(const std::uint8_t* p, std::size_t n) {
    // A C string in a fixed-width field: what follows its NUL is a buffer's leftover ("LFHD\0ab").
    n = std::find(p, p + n, std::uint8_t(0)) - p;
    while (n > 0 && (p[n - 1] == ' ' || p[n - 1] == 0)) --n;
    std::size_t b = 0;
    while (b < n && p[b] == ' ') ++b;
    return std::string(reinterpret_cast<const char*>(p) + b, n - b);
}
}  // namespace

void C3dParameter::assign(C3dParamType type, std::vector<int> dims, std::vector<std::uint8_t> bytes,
                          std::vector<std::int16_t> ints, std::vector<float> floats) {
    for (int d : dims)
        if (d < 0 || d > 255) throw std::invalid_argument("C3D parameter dimension out of 0..255");
    if (dims.size() > 7) throw std::invalid_argument("C3D parameter has more than 7 dimensions");
    const std::size_t n = product(dims);
    const bool ok = (type == C3dParamType::Char || type == C3dParamType::Byte)
                        ? bytes.size() == n && ints.empty() && floats.empty()
                    : type == C3dParamType::Int16
                        ? ints.size() == n && bytes.empty() && floats.empty()
                        : floats.size() == n && bytes.empty() && ints.empty();
    if (!ok)
        throw std::invalid_argument("C3D parameter " + name + ": values do not match dimensions");
    type_ = type;
    dims_ = std::move(dims);
    bytes_ = std::move(bytes);
    ints_ = std::move(ints);
    floats_ = std::move(floats);
}

C3dParameter C3dParameter::chars(std::string name, const std::vector<std::string>& values,
                                 std::size_t width) {
    for (const auto& v : values) width = std::max(width, v.size());
    if (width > 255) throw std::invalid_argument("C3D string longer than 255 characters: " + name);
    if (values.size() > 255)
        throw std::invalid_argument("C3D parameter " + name + " holds more than 255 strings");
    std::vector<std::uint8_t> bytes(width * values.size(), ' ');
    for (std::size_t i = 0; i < values.size(); ++i)
        std::copy(values[i].begin(), values[i].end(), bytes.begin() + i * width);
    C3dParameter p;
    p.name = std::move(name);
    std::vector<int> dims{int(width)};
    if (values.size() != 1) dims.push_back(int(values.size()));
    p.assign(C3dParamType::Char, std::move(dims), std::move(bytes), {}, {});
    return p;
}

C3dParameter C3dParameter::int16s(std::string name, std::vector<std::int16_t> values,
                                  std::vector<int> dims) {
    if (dims.empty() && values.size() != 1) dims.push_back(int(values.size()));
    C3dParameter p;
    p.name = std::move(name);
    p.assign(C3dParamType::Int16, std::move(dims), {}, std::move(values), {});
    return p;
}

C3dParameter C3dParameter::floats(std::string name, std::vector<float> values,
                                  std::vector<int> dims) {
    if (dims.empty() && values.size() != 1) dims.push_back(int(values.size()));
    C3dParameter p;
    p.name = std::move(name);
    p.assign(C3dParamType::Float, std::move(dims), {}, {}, std::move(values));
    return p;
}

C3dParameter C3dParameter::bytes(std::string name, std::vector<std::uint8_t> values,
                                 std::vector<int> dims) {
    if (dims.empty() && values.size() != 1) dims.push_back(int(values.size()));
    C3dParameter p;
    p.name = std::move(name);
    p.assign(C3dParamType::Byte, std::move(dims), std::move(values), {}, {});
    return p;
}

std::size_t C3dParameter::elementCount() const {
    switch (type_) {
        case C3dParamType::Int16:
            return ints_.size();
        case C3dParamType::Float:
            return floats_.size();
        default:
            return bytes_.size();
    }
}

std::optional<double> C3dParameter::number(std::size_t i, bool unsignedInt16) const {
    switch (type_) {
        case C3dParamType::Int16:
            if (i >= ints_.size()) return std::nullopt;
            return unsignedInt16 ? double(std::uint16_t(ints_[i])) : double(ints_[i]);
        case C3dParamType::Float:
            if (i >= floats_.size()) return std::nullopt;
            return double(floats_[i]);
        case C3dParamType::Byte:
            if (i >= bytes_.size()) return std::nullopt;
            return double(bytes_[i]);
        case C3dParamType::Char:
        default:
            return std::nullopt;
    }
}

std::vector<double> C3dParameter::numbers(bool unsignedInt16) const {
    std::vector<double> out;
    if (type_ == C3dParamType::Char) return out;
    const std::size_t n = elementCount();
    out.reserve(n);
    for (std::size_t i = 0; i < n; ++i) out.push_back(*number(i, unsignedInt16));
    return out;
}

std::vector<std::string> C3dParameter::strings() const {
    std::vector<std::string> out;
    if (type_ != C3dParamType::Char) return out;
    if (dims_.size() <= 1) {
        out.push_back(trimmed(bytes_.data(), bytes_.size()));
        return out;
    }
    const std::size_t width = static_cast<std::size_t>(dims_[0]);
    const std::size_t count = width == 0 ? 0 : bytes_.size() / width;
    // A zero-width array holds no characters, however many strings its other dimensions
    // claim (a file can claim 255^6 of them).
    if (width == 0) return out;
    out.reserve(count);
    for (std::size_t i = 0; i < count; ++i)
        out.push_back(trimmed(bytes_.data() + i * width, width));
    return out;
}

std::string C3dParameter::string() const {
    if (type_ != C3dParamType::Char) return {};
    return trimmed(bytes_.data(), bytes_.size());
}

const C3dParameter* C3dGroup::find(std::string_view parameter) const {
    for (const auto& p : parameters)
        if (c3dNameEquals(p.name, parameter)) return &p;
    return nullptr;
}

C3dParameter* C3dGroup::find(std::string_view parameter) {
    for (auto& p : parameters)
        if (c3dNameEquals(p.name, parameter)) return &p;
    return nullptr;
}

C3dParameter& C3dGroup::set(C3dParameter parameter) {
    if (C3dParameter* existing = find(parameter.name)) {
        *existing = std::move(parameter);
        return *existing;
    }
    parameters.push_back(std::move(parameter));
    return parameters.back();
}

bool C3dGroup::remove(std::string_view parameter) {
    auto it = std::find_if(parameters.begin(), parameters.end(),
                           [&](const C3dParameter& p) { return c3dNameEquals(p.name, parameter); });
    if (it == parameters.end()) return false;
    parameters.erase(it);
    return true;
}

const C3dGroup* C3dParameters::group(std::string_view name) const {
    for (const auto& g : groups_)
        if (c3dNameEquals(g.name, name)) return &g;
    return nullptr;
}

C3dGroup* C3dParameters::group(std::string_view name) {
    for (auto& g : groups_)
        if (c3dNameEquals(g.name, name)) return &g;
    return nullptr;
}

C3dGroup& C3dParameters::addGroup(std::string name, std::string description) {
    if (C3dGroup* g = group(name)) return *g;
    groups_.push_back(C3dGroup{std::move(name), std::move(description), false, {}});
    return groups_.back();
}

bool C3dParameters::removeGroup(std::string_view name) {
    auto it = std::find_if(groups_.begin(), groups_.end(),
                           [&](const C3dGroup& g) { return c3dNameEquals(g.name, name); });
    if (it == groups_.end()) return false;
    groups_.erase(it);
    return true;
}

const C3dParameter* C3dParameters::find(std::string_view groupName,
                                        std::string_view parameter) const {
    const C3dGroup* g = group(groupName);
    return g ? g->find(parameter) : nullptr;
}

C3dParameter& C3dParameters::set(std::string_view groupName, C3dParameter parameter) {
    return addGroup(std::string(groupName)).set(std::move(parameter));
}

std::vector<std::string> C3dParameters::continuedStrings(std::string_view groupName,
                                                         std::string_view name) const {
    std::vector<std::string> out;
    const C3dGroup* g = group(groupName);
    if (!g) return out;
    for (int k = 1; k < 1000; ++k) {
        const std::string key = k == 1 ? std::string(name) : std::string(name) + std::to_string(k);
        const C3dParameter* p = g->find(key);
        if (!p) break;
        for (auto& s : p->strings()) out.push_back(std::move(s));
    }
    return out;
}

}  // namespace boneless

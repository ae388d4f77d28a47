#pragma once

// The parameter tree of a C3D file: groups (POINT, ANALOG, TRIAL, ...) holding typed, possibly
// multi-dimensional parameters. Names compare case-insensitively, as the format specifies.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace boneless {

enum class C3dParamType : std::int8_t { Char = -1, Byte = 1, Int16 = 2, Float = 4 };

class C3dParameter {
  public:
    std::string name;
    std::string description;
    bool locked = false;
    std::int64_t fileOffset = -1;  // where the record starts in the file it was read from

    static C3dParameter chars(std::string name, const std::vector<std::string>& values,
                              std::size_t width = 0);
    static C3dParameter int16s(std::string name, std::vector<std::int16_t> values,
                               std::vector<int> dims = {});
    static C3dParameter floats(std::string name, std::vector<float> values,
                               std::vector<int> dims = {});
    static C3dParameter bytes(std::string name, std::vector<std::uint8_t> values,
                              std::vector<int> dims = {});

    C3dParamType type() const { return type_; }
    // Dimensions as stored, first varying fastest; empty for a scalar.
    const std::vector<int>& dims() const { return dims_; }
    // Number of stored elements (characters for Char).
    std::size_t elementCount() const;

    // Element i as a number: Int16 signed, Byte unsigned, Float as is; nullopt if out of range or
    // Char. unsignedInt16 reads Int16 as 0..65535, which counts such as POINT:USED need.
    std::optional<double> number(std::size_t i = 0, bool unsignedInt16 = false) const;
    std::vector<double> numbers(bool unsignedInt16 = false) const;

    // Char arrays: the first dimension is the string length, the others the count of strings;
    // trailing spaces and NULs are trimmed. A 1-D array is one string.
    std::vector<std::string> strings() const;
    std::string string() const;

    const std::vector<std::uint8_t>& rawBytes() const { return bytes_; }
    const std::vector<std::int16_t>& rawInt16s() const { return ints_; }
    const std::vector<float>& rawFloats() const { return floats_; }

    // Used by the parser; validates that the value count matches the dimensions.
    void assign(C3dParamType type, std::vector<int> dims, std::vector<std::uint8_t> bytes,
                std::vector<std::int16_t> ints, std::vector<float> floats);

  private:
    C3dParamType type_ = C3dParamType::Int16;
    std::vector<int> dims_;
    std::vector<std::uint8_t> bytes_;
    std::vector<std::int16_t> ints_;
    std::vector<float> floats_;
};

struct C3dGroup {
    std::string name;
    std::string description;
    bool locked = false;
    std::vector<C3dParameter> parameters;

    const C3dParameter* find(std::string_view parameter) const;
    C3dParameter* find(std::string_view parameter);
    // Adds or replaces (by name) a parameter.
    C3dParameter& set(C3dParameter parameter);
    bool remove(std::string_view parameter);
};

class C3dParameters {
  public:
    const std::vector<C3dGroup>& groups() const { return groups_; }
    const C3dGroup* group(std::string_view name) const;
    C3dGroup* group(std::string_view name);
    C3dGroup& addGroup(std::string name, std::string description = {});
    bool removeGroup(std::string_view name);
    const C3dParameter* find(std::string_view group, std::string_view parameter) const;
    C3dParameter& set(std::string_view group, C3dParameter parameter);

    // Strings of NAME, NAME2, NAME3, ... concatenated: how POINT:LABELS and friends continue
    // past 255 entries. Stops at the first missing continuation.
    std::vector<std::string> continuedStrings(std::string_view group, std::string_view name) const;

  private:
    std::vector<C3dGroup> groups_;
};

bool c3dNameEquals(std::string_view a, std::string_view b);

}  // namespace boneless

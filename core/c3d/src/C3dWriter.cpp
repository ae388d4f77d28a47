// Writing a take as an Intel, float C3D file.

#include "boneless/C3dWriter.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <stdexcept>

#include "C3dDetail.h"
#include "boneless/C3dError.h"
#include "boneless/Text.h"

namespace boneless {

namespace {

constexpr std::size_t kBlock = 512;
constexpr C3dProcessor kIntel = C3dProcessor::Intel;

std::int16_t asWord(std::size_t v) {
    return static_cast<std::int16_t>(static_cast<std::uint16_t>(v));
}

bool isContinuation(const std::string& name, const char* base) {
    const std::size_t n = std::strlen(base);
    if (name.size() <= n || !c3dNameEquals(std::string_view(name).substr(0, n), base)) return false;
    for (std::size_t i = n; i < name.size(); ++i)
        if (!isAsciiDigit(name[i])) return false;
    return true;
}

void removeList(C3dGroup& g, const char* base) {
    g.remove(base);
    auto& ps = g.parameters;
    ps.erase(std::remove_if(ps.begin(), ps.end(),
                            [&](const C3dParameter& p) { return isContinuation(p.name, base); }),
             ps.end());
}

// NAME, NAME2, NAME3, ...: at most 255 strings each, and few enough that the record's 16-bit
// offset can still reach the next one.
void setList(C3dGroup& g, const char* base, const std::vector<std::string>& values) {
    removeList(g, base);
    if (values.empty()) return;
    std::size_t width = 1;
    for (const auto& v : values) width = std::max(width, v.size());
    if (width > 255)
        throw std::invalid_argument(std::string("C3D writer: a POINT:") + base +
                                    " entry is longer than 255 characters");
    const std::size_t perParam = std::min<std::size_t>(255, 32000 / width);
    for (std::size_t first = 0, k = 1; first < values.size(); first += perParam, ++k) {
        const std::size_t last = std::min(values.size(), first + perParam);
        std::vector<std::string> chunk(values.begin() + first, values.begin() + last);
        C3dParameter p =
            C3dParameter::chars(k == 1 ? base : base + std::to_string(k), chunk, width);
        // A single string must still be an array of one, or readers take it as one long string.
        if (p.dims().size() == 1)
            p.assign(C3dParamType::Char, {int(width), 1}, p.rawBytes(), {}, {});
        g.parameters.push_back(std::move(p));
    }
}

class Out {
  public:
    std::vector<std::uint8_t> bytes;
    void u8(std::uint8_t v) { bytes.push_back(v); }
    void i8(int v) { bytes.push_back(static_cast<std::uint8_t>(static_cast<std::int8_t>(v))); }
    void u16(std::uint16_t v) {
        bytes.push_back(static_cast<std::uint8_t>(v & 0xFF));
        bytes.push_back(static_cast<std::uint8_t>(v >> 8));
    }
    void f32(float v) {
        const std::size_t at = bytes.size();
        bytes.resize(at + 4);
        c3d::putF32(bytes.data() + at, v);
    }
    void str(const std::string& s) { bytes.insert(bytes.end(), s.begin(), s.end()); }
};

void checkName(const std::string& name) {
    if (name.empty() || name.size() > 127)
        throw std::invalid_argument("C3D writer: name \"" + name +
                                    "\" must have 1..127 characters");
    // Spaces as the reader accepts them, so a file read and written keeps its names.
    for (unsigned char c : name)
        if (c < 0x20 || c > 0x7E)
            throw std::invalid_argument("C3D writer: name \"" + name +
                                        "\" has a character outside printable ASCII");
}

std::string clipped(const std::string& s) {
    return s.size() > 255 ? s.substr(0, 255) : s;
}

std::vector<std::uint8_t> encodeParameters(const C3dParameters& ps) {
    Out o;
    o.u8(1);
    o.u8(0x50);
    o.u8(0);  // block count, patched below
    o.u8(static_cast<std::uint8_t>(kIntel));
    std::size_t lastOffsetAt = 0;
    const auto& groups = ps.groups();
    if (groups.size() > 127) throw std::invalid_argument("C3D writer: more than 127 groups");
    for (std::size_t gi = 0; gi < groups.size(); ++gi) {
        const C3dGroup& g = groups[gi];
        const int id = int(gi) + 1;
        checkName(g.name);
        const std::string gdesc = clipped(g.description);
        o.i8(g.locked ? -int(g.name.size()) : int(g.name.size()));
        o.i8(-id);
        o.str(g.name);
        lastOffsetAt = o.bytes.size();
        o.u16(static_cast<std::uint16_t>(2 + 1 + gdesc.size()));
        o.u8(static_cast<std::uint8_t>(gdesc.size()));
        o.str(gdesc);
        for (const C3dParameter& p : g.parameters) {
            checkName(p.name);
            const std::string desc = clipped(p.description);
            const std::size_t elem = p.type() == C3dParamType::Int16   ? 2
                                     : p.type() == C3dParamType::Float ? 4
                                                                       : 1;
            const std::size_t dataSize = p.elementCount() * elem;
            const std::size_t offset = 2 + 1 + 1 + p.dims().size() + dataSize + 1 + desc.size();
            if (offset > 32767)
                throw std::invalid_argument("C3D writer: parameter " + g.name + ":" + p.name +
                                            " is too large for one record");
            o.i8(p.locked ? -int(p.name.size()) : int(p.name.size()));
            o.i8(id);
            o.str(p.name);
            lastOffsetAt = o.bytes.size();
            o.u16(static_cast<std::uint16_t>(offset));
            o.i8(static_cast<int>(p.type()));
            o.u8(static_cast<std::uint8_t>(p.dims().size()));
            for (int d : p.dims()) o.u8(static_cast<std::uint8_t>(d));
            if (p.type() == C3dParamType::Int16) {
                for (std::int16_t v : p.rawInt16s()) o.u16(static_cast<std::uint16_t>(v));
            } else if (p.type() == C3dParamType::Float) {
                for (float v : p.rawFloats()) o.f32(v);
            } else {
                o.bytes.insert(o.bytes.end(), p.rawBytes().begin(), p.rawBytes().end());
            }
            o.u8(static_cast<std::uint8_t>(desc.size()));
            o.str(desc);
        }
    }
    // The last record's offset is 0; zero padding after it ends the section for readers that
    // look for a zero name length instead.
    if (lastOffsetAt) o.bytes[lastOffsetAt] = o.bytes[lastOffsetAt + 1] = 0;
    const std::size_t blocks = (o.bytes.size() + 1 + kBlock - 1) / kBlock;
    if (blocks > 255)
        throw std::invalid_argument("C3D writer: parameter section exceeds 255 blocks");
    o.bytes.resize(blocks * kBlock, 0);
    o.bytes[2] = static_cast<std::uint8_t>(blocks);
    return std::move(o.bytes);
}

// Every value a float field is given must fit a float (converting one that does not is undefined).
bool fitsFloat(double v) {
    return !(std::fabs(v) > double(std::numeric_limits<float>::max()));
}

// The frame numbering and scaling that the header and the parameters both state.
struct Layout {
    std::size_t frames = 0, points = 0;
    float scale = -1.0f;  // negative: float storage
    float rate = 0.0f;
    std::int64_t first = 1, last = 0;
    // Two separate limits of 16-bit fields: the frame count (POINT:FRAMES) and the frame numbers
    // (header words 4 and 5; a first frame beyond them survives only in TRIAL).
    bool longCount = false, headerRange = true;
};

Layout layoutOf(const C3dTake& take) {
    Layout l;
    l.frames = take.samples.frames();
    l.points = take.samples.points();
    if (take.points.size() != l.points)
        throw std::invalid_argument("C3D writer: " + std::to_string(take.points.size()) +
                                    " point descriptions for " + std::to_string(l.points) +
                                    " sample columns");
    if (l.points > 65535) throw std::invalid_argument("C3D writer: more than 65535 points");
    if (l.frames > 2147483647u) throw std::invalid_argument("C3D writer: too many frames");
    if (!fitsFloat(take.rate) || !fitsFloat(take.pointScale))
        throw std::invalid_argument("C3D writer: rate or scale outside the float range");
    if (std::isfinite(take.pointScale) && take.pointScale != 0.0)
        l.scale = -static_cast<float>(std::fabs(take.pointScale));
    l.rate = static_cast<float>(take.rate);
    l.first = take.firstFrame >= 1 ? take.firstFrame : 1;
    l.last = l.first + std::int64_t(l.frames) - 1;
    if (l.last > 4294967295LL)
        throw std::invalid_argument("C3D writer: frame numbers beyond 32 bits");
    l.longCount = l.frames > 65535;
    l.headerRange = l.last <= 65535;
    return l;
}

// POINT as this file's samples and points state it; lists named by a previous TYPE_GROUPS would
// go stale, so the standard names replace them.
void setPointGroup(C3dParameters& ps, const C3dTake& take, const C3dWriteOptions& options,
                   const Layout& l) {
    C3dGroup& pt = ps.addGroup("POINT", "3-D point parameters");
    if (const C3dParameter* tg = pt.find("TYPE_GROUPS")) {
        const auto s = tg->strings();
        for (std::size_t i = 0; i < s.size(); i += 2) removeList(pt, s[i].c_str());
        pt.remove("TYPE_GROUPS");
    }
    pt.set(C3dParameter::int16s("USED", {asWord(l.points)}, {}));
    pt.set(C3dParameter::floats("SCALE", {l.scale}, {}));
    pt.set(C3dParameter::floats("RATE", {l.rate}, {}));
    pt.set(C3dParameter::chars(
        "UNITS", {take.units.empty() ? std::string("mm")
                                     : c3d_detail::textToC3d(take.units, take.textEncoding)}));
    pt.remove("LONG_FRAMES");
    if (!l.longCount) {
        pt.set(C3dParameter::int16s("FRAMES", {asWord(l.frames)}, {}));
    } else if (options.trialFrameRange || options.longFrames) {
        pt.set(C3dParameter::int16s("FRAMES", {asWord(65535)}, {}));
        if (options.longFrames) pt.set(C3dParameter::floats("LONG_FRAMES", {float(l.frames)}, {}));
    } else {
        pt.set(C3dParameter::floats("FRAMES", {float(l.frames)}, {}));
    }
    std::vector<std::string> labels, descriptions;
    std::vector<std::string> byKind[7];
    bool anyDescription = false;
    const C3dTextEncoding enc = take.textEncoding;
    for (const C3dPoint& p : take.points) {
        labels.push_back(c3d_detail::textToC3d(p.label, enc));
        descriptions.push_back(c3d_detail::textToC3d(p.description, enc));
        anyDescription = anyDescription || !p.description.empty();
        byKind[static_cast<int>(p.kind)].push_back(labels.back());
    }
    setList(pt, "LABELS", labels);
    setList(pt, "DESCRIPTIONS", anyDescription ? descriptions : std::vector<std::string>{});
    setList(pt, "ANGLES", byKind[int(C3dPointKind::Angle)]);
    setList(pt, "FORCES", byKind[int(C3dPointKind::Force)]);
    setList(pt, "MOMENTS", byKind[int(C3dPointKind::Moment)]);
    setList(pt, "POWERS", byKind[int(C3dPointKind::Power)]);
    setList(pt, "SCALARS", byKind[int(C3dPointKind::Scalar)]);
    removeList(pt, "REACTIONS");
}

// TRIAL's 32-bit frame range, for counts and frame numbers the 16-bit fields cannot hold.
void setTrialRange(C3dParameters& ps, const C3dWriteOptions& options, const Layout& l) {
    const C3dGroup* trial = ps.group("TRIAL");
    if (!(l.longCount && options.trialFrameRange) && l.first <= 65535 &&
        !(trial && trial->find("ACTUAL_START_FIELD")))
        return;
    C3dGroup& tr = ps.addGroup("TRIAL");
    auto words = [](std::int64_t v) {
        return std::vector<std::int16_t>{asWord(std::size_t(v) & 0xFFFF),
                                         asWord((std::size_t(v) >> 16) & 0xFFFF)};
    };
    tr.set(C3dParameter::int16s("ACTUAL_START_FIELD", words(l.first), {2}));
    // Without frames the range is empty; end = start keeps it well-formed, and POINT:FRAMES
    // (0, not 65535) is what readers take the count from.
    tr.set(C3dParameter::int16s("ACTUAL_END_FIELD", words(l.frames ? l.last : l.first), {2}));
}

void putHeader(std::uint8_t* out, const Layout& l, std::size_t dataBlock) {
    out[0] = 2;
    out[1] = 0x50;
    c3d::putU16(&out[2], static_cast<std::uint16_t>(l.points));
    c3d::putU16(&out[4], 0);
    const std::uint16_t firstWord = l.headerRange ? static_cast<std::uint16_t>(l.first) : 1;
    const std::uint16_t lastWord =
        l.frames == 0 ? 0
                      : static_cast<std::uint16_t>(
                            l.headerRange ? l.last : std::min<std::int64_t>(l.frames, 65535));
    c3d::putU16(&out[6], firstWord);
    c3d::putU16(&out[8], lastWord);
    c3d::putU16(&out[10], 10);
    c3d::putF32(&out[12], l.scale);
    c3d::putU16(&out[16], static_cast<std::uint16_t>(dataBlock));
    c3d::putU16(&out[18], 0);
    c3d::putF32(&out[20], l.rate);
    c3d::putU16(&out[298], 0x3039);  // word 150: event labels are 4 characters
}

// Float samples: x, y, z, then the residual in scale units (-1: not seen).
void putFrames(std::uint8_t* w, const C3dTake& take, const Layout& l) {
    const float residualStep = std::fabs(l.scale);
    for (std::size_t f = 0; f < l.frames && l.points > 0; ++f) {
        for (std::size_t k = 0; k < l.points; ++k, w += 16) {
            const auto xyz = take.samples.position(f, k);
            if (!xyz) {
                c3d::putF32(w, 0.0f);
                c3d::putF32(w + 4, 0.0f);
                c3d::putF32(w + 8, 0.0f);
                c3d::putF32(w + 12, -1.0f);
                continue;
            }
            if (!fitsFloat(xyz->x()) || !fitsFloat(xyz->y()) || !fitsFloat(xyz->z()))
                throw std::invalid_argument("C3D writer: sample (" + std::to_string(f) + ", " +
                                            std::to_string(k) + ") is outside the float range");
            c3d::putF32(w, static_cast<float>(xyz->x()));
            c3d::putF32(w + 4, static_cast<float>(xyz->y()));
            c3d::putF32(w + 8, static_cast<float>(xyz->z()));
            const double r = std::round(take.samples.residual(f, k) / residualStep);
            c3d::putF32(w + 12, static_cast<float>(std::clamp(r, 0.0, 255.0)));
        }
    }
}

}  // namespace

std::vector<std::uint8_t> encodeC3d(const C3dTake& take, const C3dWriteOptions& options) {
    const Layout l = layoutOf(take);
    C3dParameters ps = take.parameters;
    setPointGroup(ps, take, options, l);
    ps.addGroup("ANALOG", "analog data parameters");
    ps.set("ANALOG", C3dParameter::int16s("USED", {0}, {}));
    ps.set("ANALOG", C3dParameter::floats("RATE", {l.rate}, {}));
    setTrialRange(ps, options, l);

    // DATA_START depends on the section's size, which DATA_START itself is part of: write a
    // placeholder of the same size first.
    ps.set("POINT", C3dParameter::int16s("DATA_START", {0}, {}));
    std::vector<std::uint8_t> params = encodeParameters(ps);
    const std::size_t dataBlock = 2 + params.size() / kBlock;
    if (dataBlock > 32767) throw std::invalid_argument("C3D writer: parameter section too large");
    ps.set("POINT", C3dParameter::int16s("DATA_START", {asWord(dataBlock)}, {}));
    params = encodeParameters(ps);

    // One allocation for the whole file: header, parameters, then the frames.
    const std::size_t dataAt = kBlock + params.size();
    std::vector<std::uint8_t> out(dataAt + l.frames * l.points * 16, 0);
    std::memcpy(out.data() + kBlock, params.data(), params.size());
    putHeader(out.data(), l, dataBlock);
    putFrames(out.data() + dataAt, take, l);
    return out;
}

void writeC3d(const C3dTake& take, const std::string& path, const C3dWriteOptions& options) {
    const std::vector<std::uint8_t> bytes = encodeC3d(take, options);
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    if (!out)
        throw C3dError(path, C3dError::kNoOffset,
                       std::string("cannot write: ") + std::strerror(errno));
    out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    if (!out) throw C3dError(path, C3dError::kNoOffset, "write failed");
}

}  // namespace boneless

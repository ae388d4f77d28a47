// Reading a C3D file: locate the sections, reconcile the header with the parameters, decode.

#include "boneless/C3dReader.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "C3dDetail.h"

namespace boneless {

using namespace c3d_detail;

std::optional<double> c3dUnitToMm(std::string_view units) {
    std::string u;
    for (char c : units)
        if (std::isalpha(static_cast<unsigned char>(c)))
            u.push_back(static_cast<char>(std::tolower(static_cast<unsigned char>(c))));
    if (u == "mm") return 1.0;
    if (u == "cm") return 10.0;
    if (u == "dm") return 100.0;
    if (u == "m") return 1000.0;
    if (u == "in") return 25.4;
    if (u == "ft") return 304.8;
    // Writers truncate the string to the space they allotted ("mete", "millim"): accept any
    // prefix of at least three letters of a spelled-out unit.
    static const std::pair<const char*, double> spelled[] = {
        {"millimeters", 1.0},  {"millimetres", 1.0},  {"centimeters", 10.0}, {"centimetres", 10.0},
        {"decimeters", 100.0}, {"decimetres", 100.0}, {"meters", 1000.0},    {"metres", 1000.0},
        {"inches", 25.4},      {"feet", 304.8},       {"foot", 304.8}};
    if (u.size() >= 3)
        for (const auto& [word, mm] : spelled)
            if (std::string_view(word).substr(0, u.size()) == u) return mm;
    return std::nullopt;
}

namespace {

std::string fmt(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

std::optional<double> paramNumber(const C3dParameters& ps, const char* group, const char* name,
                                  bool unsignedInt16 = true) {
    const C3dParameter* p = ps.find(group, name);
    return p ? p->number(0, unsignedInt16) : std::nullopt;
}

// TRIAL:ACTUAL_START_FIELD / ACTUAL_END_FIELD: a 32-bit frame number as two 16-bit words, least
// significant first.
std::optional<std::int64_t> trialField(const C3dParameters& ps, const char* name) {
    const C3dParameter* p = ps.find("TRIAL", name);
    if (!p) return std::nullopt;
    const auto lo = p->number(0, true), hi = p->number(1, true);
    if (!lo) return std::nullopt;
    if (p->type() == C3dParamType::Float) {
        if (!(*lo >= 0.0 && *lo <= 4294967295.0)) return std::nullopt;
        return std::int64_t(*lo);
    }
    return std::int64_t(*lo) + (hi ? std::int64_t(*hi) * 65536 : 0);
}

bool isCount(double v, double max) {
    return std::isfinite(v) && v >= 0 && v <= max && v == std::floor(v);
}

// A count from the parameters that is not a whole number in [0, max] (NaN, negative, 1e30) is
// ignored in favour of the header's, with a warning.
std::size_t countOr(std::vector<std::string>& warn, double v, double max, const std::string& what,
                    std::size_t fallback) {
    if (isCount(v, max)) return static_cast<std::size_t>(v);
    warn.push_back(what + " is " + fmt(v) + ", not a count; using the header's " +
                   std::to_string(fallback));
    return fallback;
}

}  // namespace

namespace c3d_detail {

PointLayout readTakeLayout(const Source& src, const C3dReadOptions& options, C3dTake& take) {
    const std::uint8_t* data = src.data;
    const std::size_t size = src.size;
    const std::string& name = src.file;
    if (size == 0) src.fail(0, "empty file (0 bytes), not a C3D file");
    if (size < kBlock)
        src.fail(size, "file is " + std::to_string(size) +
                           " bytes, too short for the 512-byte C3D header");
    if (data[1] != 0x50)
        src.fail(1, "not a C3D file: header byte 2 is " + std::to_string(data[1]) +
                        ", the C3D key is 80 (0x50)");

    take.file = name;
    auto& warn = take.warnings;

    // The processor type lives in the parameter section, found through the header's pointer
    // (never assumed to be block 2).
    const std::size_t paramBlock = data[0];
    const bool haveParams = paramBlock >= 2 && (paramBlock - 1) * kBlock + 4 <= size;
    const std::size_t paramStart = haveParams ? (paramBlock - 1) * kBlock : 0;
    C3dProcessor proc = C3dProcessor::Intel;
    if (haveParams) {
        const int type = data[paramStart + 3];
        if (type >= 84 && type <= 86) {
            proc = static_cast<C3dProcessor>(type);
        } else {
            proc = guessHeaderProcessor(src);
            warn.push_back("unknown processor type " + std::to_string(type) + " at byte " +
                           std::to_string(paramStart + 3) + "; the header reads as " +
                           toString(proc));
        }
    } else {
        proc = guessHeaderProcessor(src);
        warn.push_back("no parameter section (the header points to block " +
                       std::to_string(paramBlock) + "); using the header only, which reads as " +
                       toString(proc));
    }
    take.processor = proc;
    const HeaderWords h = readHeaderWords(src, proc);
    take.firstFrameWord = h.firstFrame;
    take.lastFrameWord = h.lastFrame;

    const std::size_t headerDataStart =
        h.dataStartBlock >= 1 ? (std::size_t(h.dataStartBlock) - 1) * kBlock : 0;
    if (haveParams) {
        // Records run to their real end, which may lie past the declared block count, but they
        // cannot run into the 3D data.
        const bool dataAfter = headerDataStart > paramStart && headerDataStart < size;
        take.parameters =
            readParameterSection(src, paramStart, dataAfter ? headerDataStart : size,
                                 dataAfter ? "the start of the 3D data" : "the end of the file",
                                 proc, data[paramStart + 2], warn);
    }
    const C3dParameters& ps = take.parameters;

    // Point count: trust the parameters, say so when the header disagrees.
    std::size_t points = h.pointCount;
    if (auto u = paramNumber(ps, "POINT", "USED")) {
        points = countOr(warn, *u, 65535, "POINT:USED", h.pointCount);
        if (points != h.pointCount)
            warn.push_back("header says " + std::to_string(h.pointCount) +
                           " points, POINT:USED says " + std::to_string(points) +
                           "; using POINT:USED");
    }

    // Scale: its sign selects int16 (> 0) or float (< 0) storage.
    double scale = h.scale;
    if (auto s = paramNumber(ps, "POINT", "SCALE")) {
        if (std::isfinite(*s) && *s != 0.0) {
            if (std::isfinite(h.scale) && h.scale != 0.0f &&
                std::fabs(*s - h.scale) > 1e-4 * std::fabs(*s))
                warn.push_back("header scale " + fmt(h.scale) + " differs from POINT:SCALE " +
                               fmt(*s) + "; using POINT:SCALE");
            scale = *s;
        } else {
            warn.push_back("POINT:SCALE is " + fmt(*s) + "; using the header's scale " +
                           fmt(h.scale));
        }
    }

    // Rate.
    double rate = h.rate;
    if (auto r = paramNumber(ps, "POINT", "RATE")) {
        if (!(std::isfinite(*r) && *r > 0.0)) {
            warn.push_back("POINT:RATE is " + fmt(*r) + "; using the header's " + fmt(h.rate) +
                           " Hz");
        } else {
            if (std::isfinite(h.rate) && std::fabs(*r - h.rate) > 1e-3 * std::fabs(*r))
                warn.push_back("header rate " + fmt(h.rate) + " Hz differs from POINT:RATE " +
                               fmt(*r) + " Hz; using POINT:RATE");
            rate = *r;
        }
    }
    if (!std::isfinite(rate) || rate <= 0.0) {
        warn.push_back("frame rate is " + fmt(rate) + "; reported as 0");
        rate = 0.0;
    }
    take.rate = rate;

    // Text leaves the reader as UTF-8; latin1 records that some of it had to be converted.
    bool latin1 = false;

    // Units.
    if (const C3dParameter* u = ps.find("POINT", "UNITS")) {
        take.units = textFromC3d(u->string(), latin1);
        if (auto mm = c3dUnitToMm(take.units)) {
            take.unitToMm = *mm;
        } else {
            warn.push_back("unknown POINT:UNITS \"" + take.units + "\"; assuming millimetres");
        }
    } else {
        warn.push_back("no POINT:UNITS; assuming millimetres");
    }

    // Analog channels interleaved in each frame.
    std::size_t channels = h.analogSamplesPerFrame ? h.analogPerFrame / h.analogSamplesPerFrame : 0;
    double analogRate = double(h.analogSamplesPerFrame) * rate;
    std::size_t perFrame = h.analogSamplesPerFrame;
    if (auto u = paramNumber(ps, "ANALOG", "USED"))
        channels = countOr(warn, *u, 65535, "ANALOG:USED", channels);
    if (auto r = paramNumber(ps, "ANALOG", "RATE")) analogRate = *r;
    if (channels > 0 && ps.find("ANALOG", "RATE") && rate > 0.0) {
        const double ratio = analogRate / rate;
        if (std::isfinite(ratio) && ratio >= 0.5 && ratio <= 65535.0) {
            perFrame = static_cast<std::size_t>(std::lround(ratio));
            if (std::fabs(ratio - double(perFrame)) > 1e-3)
                warn.push_back("analog rate " + fmt(analogRate) + " Hz is not a multiple of " +
                               fmt(rate) + " Hz; assuming " + std::to_string(perFrame) +
                               " samples per frame");
        } else {
            warn.push_back("ANALOG:RATE " + fmt(analogRate) +
                           " Hz is unusable; using the header's " + std::to_string(perFrame) +
                           " samples per frame");
        }
    }
    if (!std::isfinite(analogRate) || analogRate < 0.0) analogRate = 0.0;
    take.analogChannels = static_cast<int>(channels);
    take.analogRate = channels > 0 ? analogRate : 0.0;
    take.analogSamplesPerFrame = channels > 0 ? static_cast<int>(perFrame) : 0;

    // Frame count (POINT:FRAMES, then the vendors' ways past 65535, then the header).
    const std::size_t headerFrames =
        h.lastFrame >= h.firstFrame && h.lastFrame > 0 ? h.lastFrame - h.firstFrame + 1 : 0;
    const auto framesParam = paramNumber(ps, "POINT", "FRAMES");
    const auto trialStart = trialField(ps, "ACTUAL_START_FIELD");
    const auto trialEnd = trialField(ps, "ACTUAL_END_FIELD");
    const bool trialOk = trialStart && trialEnd && *trialEnd >= *trialStart;
    const auto longFrames = paramNumber(ps, "POINT", "LONG_FRAMES");
    double frames = double(headerFrames);
    const char* framesFrom = "the header";
    if (framesParam && *framesParam != 65535.0) {
        frames = *framesParam;
        framesFrom = "POINT:FRAMES";
    } else if (trialOk) {
        frames = double(*trialEnd - *trialStart + 1);
        framesFrom = "TRIAL:ACTUAL_START_FIELD..ACTUAL_END_FIELD";
    } else if (longFrames) {
        frames = *longFrames;
        framesFrom = "POINT:LONG_FRAMES";
    } else if (framesParam) {
        frames = 65535.0;
    }
    const std::size_t declaredFrames =
        countOr(warn, frames, 2147483647.0, std::string("the frame count from ") + framesFrom,
                headerFrames);
    if (framesParam && declaredFrames <= 65535 && declaredFrames != headerFrames)
        warn.push_back("header frames " + std::to_string(h.firstFrame) + ".." +
                       std::to_string(h.lastFrame) + " (" + std::to_string(headerFrames) +
                       ") disagree with the parameters (" + std::to_string(declaredFrames) +
                       "); using the parameters");
    take.firstFrame = trialStart ? *trialStart : std::int64_t(h.firstFrame);

    // Storage.
    PointLayout L;
    L.points = points;
    L.processor = proc;
    L.keepZeroSamples = options.keepZeroSamples;
    L.analogWords = channels * perFrame;
    if (!std::isfinite(scale) || scale == 0.0) {
        if (points > 0 || L.analogWords > 0)
            src.fail(12, "the point scale is " + fmt(scale) +
                             " in both the header and POINT:SCALE, so the storage (int16 or "
                             "float) is unknown");
        scale = -1.0;
    }
    if (h.scale != 0.0f && std::isfinite(h.scale) && (h.scale < 0) != (scale < 0))
        warn.push_back("header scale and POINT:SCALE disagree on the storage; using POINT:SCALE");
    L.storage = scale < 0 ? C3dStorage::Float : C3dStorage::Int16;
    L.scale = scale;
    take.storage = L.storage;
    take.pointScale = scale;

    // Data start: POINT:DATA_START when it lies in the file, else the header.
    std::size_t dataStart = headerDataStart;
    if (auto ds = paramNumber(ps, "POINT", "DATA_START")) {
        const std::size_t block = static_cast<std::size_t>(std::max(0.0, std::min(*ds, 65535.0)));
        if (block != h.dataStartBlock) {
            if (block >= 1 && (block - 1) * kBlock < size) {
                warn.push_back("header data start block " + std::to_string(h.dataStartBlock) +
                               " differs from POINT:DATA_START " + std::to_string(block) +
                               "; using POINT:DATA_START");
                dataStart = (block - 1) * kBlock;
            } else {
                warn.push_back("POINT:DATA_START " + std::to_string(block) +
                               " lies outside the file; using the header's block " +
                               std::to_string(h.dataStartBlock));
            }
        }
    }
    if (dataStart == 0 && (points > 0 || L.analogWords > 0))
        src.fail(16, "the 3D data start block is 0");
    L.dataStart = dataStart;

    // Header and parameters may disagree on the analog words per frame; the one the file's size
    // can hold wins.
    const std::size_t dataBytes = dataStart < size ? size - dataStart : 0;
    if (L.analogWords != h.analogPerFrame && (channels > 0 || h.analogPerFrame > 0)) {
        PointLayout alt = L;
        alt.analogWords = h.analogPerFrame;
        const auto fits = [&](const PointLayout& l) {
            return l.frameBytes() == 0 || declaredFrames <= dataBytes / l.frameBytes();
        };
        if (!fits(L) && fits(alt)) {
            warn.push_back("parameters give " + std::to_string(L.analogWords) +
                           " analog values per frame, the header " +
                           std::to_string(h.analogPerFrame) +
                           "; only the header's fits the file, using it");
            L.analogWords = alt.analogWords;
        } else {
            warn.push_back("parameters give " + std::to_string(L.analogWords) +
                           " analog values per frame, the header " +
                           std::to_string(h.analogPerFrame) + "; using the parameters");
        }
    }

    // Truncated files: keep the complete frames, say how many are lost.
    L.frames = declaredFrames;
    if (L.frameBytes() > 0 && declaredFrames > dataBytes / L.frameBytes()) {
        const std::size_t complete = dataBytes / L.frameBytes();
        if (complete == 0)
            src.fail(
                std::min(dataStart, size),
                "the 3D data section holds no complete frame: " + std::to_string(declaredFrames) +
                    " frames of " + std::to_string(L.frameBytes()) +
                    " bytes declared, the file ends at byte " + std::to_string(size));
        warn.push_back("file is truncated: " + std::to_string(declaredFrames) +
                       " frames declared, " + std::to_string(complete) +
                       " complete frames present; reading those");
        L.frames = complete;
    }

    // Labels (LABELS, LABELS2, ...) and descriptions.
    std::vector<std::string> labels = ps.continuedStrings("POINT", "LABELS");
    std::vector<std::string> descriptions = ps.continuedStrings("POINT", "DESCRIPTIONS");
    if (labels.size() < points && ps.find("POINT", "LABELS"))
        warn.push_back("POINT:LABELS holds " + std::to_string(labels.size()) + " labels for " +
                       std::to_string(points) + " points; the rest are named P<n>");
    take.points.resize(points);
    std::size_t unnamed = 0;
    for (std::size_t i = 0; i < points; ++i) {
        C3dPoint& p = take.points[i];
        if (i < labels.size()) p.label = textFromC3d(labels[i], latin1);
        if (p.label.empty()) {
            p.label = "P" + std::to_string(i + 1);
            ++unnamed;
        }
        if (i < descriptions.size()) p.description = textFromC3d(descriptions[i], latin1);
    }
    if (latin1) {
        take.textEncoding = C3dTextEncoding::Latin1;
        warn.push_back("labels, descriptions or units are not UTF-8; read as Latin-1");
    }
    if (unnamed > 0 && labels.size() >= points)
        warn.push_back(std::to_string(unnamed) + " points have empty labels; named P<n>");
    classifyPoints(ps, take.points);
    return L;
}

void noteDecodeStats(const DecodeStats& stats, const C3dReadOptions& options,
                     std::vector<std::string>& warn) {
    if (stats.nonFinite > 0)
        warn.push_back(std::to_string(stats.nonFinite) +
                       " samples have non-finite coordinates; treated as missing");
    if (stats.zeroSamples > 0 && !options.keepZeroSamples)
        warn.push_back(std::to_string(stats.zeroSamples) +
                       " samples are exactly (0, 0, 0); treated as missing");
}

}  // namespace c3d_detail

C3dTake readC3dMemory(const std::uint8_t* data, std::size_t size, const std::string& name,
                      const C3dReadOptions& options) {
    const Source src{data, size, name};
    C3dTake take;
    const PointLayout L = readTakeLayout(src, options, take);
    take.samples = C3dSamples(L.frames, L.points);
    noteDecodeStats(decodePoints(src, L, take.samples), options, take.warnings);
    return take;
}

C3dTake readC3d(const std::string& path, const C3dReadOptions& options) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw C3dError(path, C3dError::kNoOffset, "is a directory, not a C3D file");
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw C3dError(path, C3dError::kNoOffset,
                       std::string("cannot open: ") + std::strerror(errno));
    in.seekg(0, std::ios::end);
    const std::streamoff end = in.tellg();
    if (end < 0) throw C3dError(path, C3dError::kNoOffset, "cannot determine the file size");
    in.seekg(0, std::ios::beg);
    std::vector<std::uint8_t> bytes(static_cast<std::size_t>(end));
    if (!bytes.empty() && !in.read(reinterpret_cast<char*>(bytes.data()), end))
        throw C3dError(path, static_cast<std::uint64_t>(in.gcount()), "read error");
    return readC3dMemory(bytes.data(), bytes.size(), path, options);
}

}  // namespace boneless
